//! The bonded structure's sparse blocks, for an engine that works on them instead of on the
//! condensed contact zone: `K_II`, `K_Iz`, `K_zz` and the generalized loads, from which
//! `R = K_zz − K_zI K_II⁻¹ K_Iz` and `R_F = K_zI K_II⁻¹ b_I − b_z` (formulation.md §2) are
//! what [`Model::condense`] forms densely.

use faer::sparse::{SparseColMat, Triplet};

use crate::assemble::assemble;
use crate::error::FemError;
use crate::model::Model;

/// The bonded structure in generalized DOFs: the DOFs off the links (`I`, `N` of them) and the
/// links' dislocations (`z`: pair `k`'s normal link `k`, its tangential link `m + k`).
#[derive(Debug, Clone)]
pub struct BondedBlocks {
    /// `K_II` (`N × N`), symmetric positive definite when the bonded structure is stable.
    pub kii: SparseColMat<usize, f64>,
    /// `K_Iz` (`N × 2m`).
    pub kiz: SparseColMat<usize, f64>,
    /// `K_zz` (`2m × 2m`).
    pub kzz: SparseColMat<usize, f64>,
    /// The generalized loads of the constant group on `I` and on `z` (settlements included).
    pub constant: [Vec<f64>; 2],
    /// The same of the variable group (per unit `p`).
    pub variable: [Vec<f64>; 2],
    /// The same of every load case of the model, indexed like [`Model::cases`] (the load
    /// histories' loads).
    pub cases: Vec<[Vec<f64>; 2]>,
}

impl Model {
    /// The bonded structure's sparse blocks ([`BondedBlocks`]), without factorising or
    /// condensing anything. Errors: those of [`Model::validate`] and of the assembly.
    pub fn bonded_blocks(&self) -> Result<BondedBlocks, FemError> {
        self.validate()?;
        let asm = assemble(self)?;
        let (n_i, nz) = (asm.map.n_i, 2 * asm.map.m);
        let mut t = Vec::new();
        if let Some(k) = &asm.kii {
            for j in 0..k.ncols() {
                for (&i, &v) in k.row_idx_of_col_raw(j).iter().zip(k.val_of_col(j)) {
                    t.push(Triplet::new(i, j, v));
                    if i != j {
                        t.push(Triplet::new(j, i, v));
                    }
                }
            }
        }
        let sparse = |r: usize, c: usize, t: &[Triplet<usize, usize, f64>]| {
            SparseColMat::try_new_from_triplets(r, c, t)
                .map_err(|e| FemError::LinearAlgebra(format!("the bonded blocks: {e:?}")))
        };
        let kii = sparse(n_i, n_i, &t)?;
        let kiz_t: Vec<_> = asm
            .kiz
            .iter()
            .enumerate()
            .flat_map(|(r, col)| col.iter().map(move |&(i, v)| Triplet::new(i, r, v)))
            .collect();
        let kiz = sparse(n_i, nz, &kiz_t)?;
        let mut kzz_t = Vec::new();
        for j in 0..nz {
            for i in 0..nz {
                let v = asm.kzz[(i, j)];
                if v != 0.0 {
                    kzz_t.push(Triplet::new(i, j, v));
                }
            }
        }
        let kzz = sparse(nz, nz, &kzz_t)?;
        let group = |g: usize| [asm.b_i[g].clone(), asm.b_z[g].clone()];
        let cases = asm
            .cases
            .iter()
            .map(|c| [c.b_i.clone(), c.b_z.clone()])
            .collect();
        Ok(BondedBlocks {
            kii,
            kiz,
            kzz,
            constant: group(0),
            variable: group(1),
            cases,
        })
    }
}
