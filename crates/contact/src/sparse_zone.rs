//! A contact zone kept as the bonded structure's sparse blocks instead of the condensed
//! matrix: `R = K_zz − K_zI K_II⁻¹ K_Iz`, `R_F = K_zI K_II⁻¹ b_I − b_z` (formulation.md §2),
//! never formed. Its LCP (§3) is a [`SchurLcp`] for the engine that works on sparse data.

use faer::sparse::{SparseColMat, Triplet};
use unilateral_lcp::SchurLcp;

/// The blocks of the bonded structure in generalized DOFs (`I`: the DOFs off the links;
/// `z`: pair `k`'s normal link `k`, its tangential link `m + k`), the pairs' friction and gaps.
#[derive(Debug, Clone)]
pub struct SparseZone {
    /// `K_II`, symmetric positive definite.
    pub kii: SparseColMat<usize, f64>,
    /// `K_Iz`.
    pub kiz: SparseColMat<usize, f64>,
    /// `K_zz`.
    pub kzz: SparseColMat<usize, f64>,
    /// Generalized loads of the constant group on `I` and on `z`.
    pub constant: [Vec<f64>; 2],
    /// Generalized loads of the variable group (per unit `p`) on `I` and on `z`.
    pub variable: [Vec<f64>; 2],
    /// Generalized loads of every load case on `I` and on `z`, indexed like the zone's
    /// [`crate::ContactZone::cases`] (the load histories'; may be empty otherwise).
    pub cases: Vec<[Vec<f64>; 2]>,
    /// Friction coefficient per pair.
    pub friction: Vec<f64>,
    /// Initial gap per pair.
    pub gap: Vec<f64>,
}

impl SparseZone {
    /// Number of pairs.
    pub fn pairs(&self) -> usize {
        self.friction.len()
    }

    /// The rows' lexicographic priority of its LCP, as the dense LCP's
    /// ([`crate::ContactLcp::lexicographic_order`]).
    pub fn lexicographic_order(&self) -> Vec<usize> {
        crate::lcp::lexicographic_order(self.pairs())
    }

    /// The friction relations of its LCP's rows, as the dense LCP's
    /// ([`crate::ContactLcp::row_relations`]).
    pub fn row_relations(&self) -> Vec<unilateral_lcp::RowRelation> {
        crate::lcp::friction_relations(&self.friction)
    }

    /// The LCP of formulation.md §3 with `M = T R U`, `q = T (R_c − R·[η; 0])`,
    /// `d = T R_v` (`T` stacks `[I, 0]`, `[F, I]`, `[F, −I]`; `U` maps `z` to the links'
    /// dislocations `[z_n; (z_t+ − z_t-)/2]`), as `x = q0 + p·d0 + D z − C y`,
    /// `A y = qa + p·da + B z` with `A = K_II`, `B = K_Iz U`, `C = T K_zI`, `D = T K_zz U`,
    /// `q0 = −T (b_z,c + K_zz [η; 0])`, `qa = −(b_I,c + K_Iz [η; 0])`, `d0 = −T b_z,v`,
    /// `da = −b_I,v`.
    pub fn lcp(&self) -> SchurLcp {
        let m = self.pairs();
        let n = 3 * m;
        let ni = self.kii.nrows();
        let f = &self.friction;
        // The rows of T in its column z (a link), the columns of U in its row z.
        let t_col = |z: usize| -> [(usize, f64); 3] {
            let i = z % m;
            if z < m {
                [(i, 1.0), (m + i, f[i]), (2 * m + i, f[i])]
            } else {
                [(m + i, 1.0), (2 * m + i, -1.0), (usize::MAX, 0.0)]
            }
        };
        let u_row = |z: usize| -> [(usize, f64); 2] {
            let i = z % m;
            if z < m {
                [(i, 1.0), (usize::MAX, 0.0)]
            } else {
                [(m + i, 0.5), (2 * m + i, -0.5)]
            }
        };
        let (mut tb, mut tc, mut td) = (Vec::new(), Vec::new(), Vec::new());
        for z in 0..2 * m {
            let rows = self.kiz.row_idx_of_col_raw(z);
            for (&i, &v) in rows.iter().zip(self.kiz.val_of_col(z)) {
                for (c, w) in u_row(z).into_iter().filter(|e| e.0 != usize::MAX) {
                    tb.push(Triplet::new(i, c, v * w));
                }
                // K_zI = K_Izᵀ.
                for (r, w) in t_col(z).into_iter().filter(|e| e.0 != usize::MAX) {
                    tc.push(Triplet::new(r, i, w * v));
                }
            }
            let rows = self.kzz.row_idx_of_col_raw(z);
            for (&zi, &v) in rows.iter().zip(self.kzz.val_of_col(z)) {
                for (r, wr) in t_col(zi).into_iter().filter(|e| e.0 != usize::MAX) {
                    for (c, wc) in u_row(z).into_iter().filter(|e| e.0 != usize::MAX) {
                        td.push(Triplet::new(r, c, wr * v * wc));
                    }
                }
            }
        }
        let sparse = |r: usize, c: usize, t: &[Triplet<usize, usize, f64>]| {
            SparseColMat::try_new_from_triplets(r, c, t).expect("indices within the shapes")
        };
        // The gaps as dislocations of the normal links: b ← b + K [η; 0].
        let mut bi = self.constant[0].clone();
        let mut bz = self.constant[1].clone();
        for (k, &eta) in self.gap.iter().enumerate().filter(|(_, e)| **e != 0.0) {
            for (&i, &v) in self
                .kiz
                .row_idx_of_col_raw(k)
                .iter()
                .zip(self.kiz.val_of_col(k))
            {
                bi[i] += v * eta;
            }
            for (&i, &v) in self
                .kzz
                .row_idx_of_col_raw(k)
                .iter()
                .zip(self.kzz.val_of_col(k))
            {
                bz[i] += v * eta;
            }
        }
        let (d0, da) = self.load_direction(&self.variable);
        SchurLcp {
            a: self.kii.clone(),
            b: sparse(ni, n, &tb),
            c: sparse(n, ni, &tc),
            d: sparse(n, n, &td),
            q0: self.minus_t(&bz),
            qa: bi.iter().map(|v| -v).collect(),
            d0,
            da,
        }
    }

    /// The LCP's load direction `(d0, da) = (−T b_z, −b_I)` of generalized loads `[b_I, b_z]`
    /// (as [`SparseZone::lcp`] forms it of the variable group): the same LCP under another
    /// load is [`SparseZone::lcp`] with these two vectors replaced.
    pub fn load_direction(&self, load: &[Vec<f64>; 2]) -> (Vec<f64>, Vec<f64>) {
        (self.minus_t(&load[1]), load[0].iter().map(|v| -v).collect())
    }

    /// `−T b` for `b` on the links (`T` stacks `[I, 0]`, `[F, I]`, `[F, −I]`).
    fn minus_t(&self, b: &[f64]) -> Vec<f64> {
        let m = self.pairs();
        let f = &self.friction;
        let mut out = vec![0.0; 3 * m];
        for (z, &v) in b.iter().enumerate() {
            let i = z % m;
            if z < m {
                out[i] -= v;
                out[m + i] -= f[i] * v;
                out[2 * m + i] -= f[i] * v;
            } else {
                out[m + i] -= v;
                out[2 * m + i] += v;
            }
        }
        out
    }
}
