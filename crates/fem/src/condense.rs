//! The condensation of a model to its contact zone (formulation.md §2): the entry point
//! [`Model::condense`], its result [`Condensed`], and the memory and time it takes.
//!
//! The steps have their own modules: the DOF numbering with link DOFs (`dofs`), the sparse
//! assembly (`assemble`), the factorization and stability diagnosis (`stability`), the Schur
//! complement (`schur`); the recovery of full results is `recover`.
//!
//! With `u = T·[v_I; z; s]`, the bonded structure (`z = 0`) has stiffness
//! `K_II = T_Iᵀ K T_I` (symmetric positive definite when stable, sparse Cholesky), and
//! `R = K_zz − K_zI K_II⁻¹ K_Iz` (the Schur complement), `R_F = K_zI K_II⁻¹ b_I − b_z`.

use crate::assemble::{assemble, Assembled};
use crate::error::FemError;
use crate::model::{CaseId, LoadGroup, Model};
use crate::results::{ContactLoadVector, LinkValues};
use crate::schur::{condense, CHUNK, ROUND_OFF};
use crate::stability::factorize;
use faer::sparse::linalg::solvers::Llt;
use faer::Mat;
use std::time::Instant;

/// The structure condensed to its contact zone (formulation.md §2), ready for the LCP, plus
/// what is needed to recover full results.
///
/// ```
/// use unilateral_fem::{ContactPairSpec, FrameSection, LinkValues, Load, LoadGroup, Model};
/// let mut model = Model::new();
/// let a = model.add_node(0.0, 0.0);
/// let b = model.add_node(2.0, 0.0);
/// model.add_frame(a, b, FrameSection::new(1.0, 1.0, 1.0));
/// model.fix(a);
/// model.add_contact_pair(ContactPairSpec::to_ground(b, [0.0, 1.0]));
/// model.add_load(LoadGroup::Variable, Load::Nodal { node: b, fx: 0.0, fy: -1.0, m: 0.0 });
/// let c = model.condense().unwrap();
/// // bonded: the link at the tip carries the whole load in compression
/// assert!((c.variable.normal[0] - 1.0).abs() < 1e-12);
/// // suppose the LCP says the pair stays closed at p = 1
/// let sol = LinkValues::bonded(&c, 1.0);
/// let r = c.recover(&sol).unwrap();
/// assert!(r.equilibrium.relative() < 1e-12);
/// ```
pub struct Condensed {
    /// Normal–normal block `Rnn` (m × m), symmetric positive semidefinite. The four blocks are
    /// `0 × 0` after [`Condensed::take_blocks`] (the condensation an analysis keeps: its
    /// contact zone holds them).
    pub rnn: Mat<f64>,
    /// `Rnt`: normal force from a tangential dislocation.
    pub rnt: Mat<f64>,
    /// `Rtn`: tangential force from a normal dislocation.
    pub rtn: Mat<f64>,
    /// `Rtt`, symmetric positive semidefinite.
    pub rtt: Mat<f64>,
    /// `R_c`: bonded link forces under the constant group.
    pub constant: ContactLoadVector,
    /// `R_v`: bonded link forces under the variable group (per unit `p`).
    pub variable: ContactLoadVector,
    /// The names of the load cases, as [`Model::cases`].
    pub case_names: Vec<String>,
    /// The bonded link forces of every load case at factor 1, indexed like `case_names`
    /// (those of the cases `constant` and `variable` are [`Condensed::constant`] and
    /// [`Condensed::variable`]).
    pub cases: Vec<ContactLoadVector>,
    /// Friction coefficient per pair.
    pub friction: Vec<f64>,
    /// Initial gap per pair.
    pub gap: Vec<f64>,
    /// Pair names.
    pub pair_names: Vec<String>,
    /// Unit normal `n` per pair (from A into B).
    pub normals: Vec<[f64; 2]>,
    /// Unit tangent `t = (n_y, −n_x)` per pair.
    pub tangents: Vec<[f64; 2]>,
    /// Sizes and timings.
    pub stats: CondensationStats,
    /// The model condensed (a copy, so that the recovery and the writers read the very model
    /// the contact zone came from).
    pub(crate) model: Model,
    pub(crate) asm: Assembled,
    pub(crate) llt: Option<Llt<usize, f64>>,
    /// The elements' global stiffness matrices and the line elements' recovery data, kept from
    /// the second recovery on (a load path's frames recover the structure thousands of times;
    /// one recovery keeps nothing).
    pub(crate) element_k: crate::recover::ElementCache,
}

impl std::fmt::Debug for Condensed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Condensed")
            .field("rnn", &self.rnn)
            .field("rnt", &self.rnt)
            .field("rtn", &self.rtn)
            .field("rtt", &self.rtt)
            .field("constant", &self.constant)
            .field("variable", &self.variable)
            .field("case_names", &self.case_names)
            .field("cases", &self.cases)
            .field("friction", &self.friction)
            .field("gap", &self.gap)
            .field("pair_names", &self.pair_names)
            .field("stats", &self.stats)
            .finish_non_exhaustive()
    }
}

impl Model {
    /// Validates the model, assembles the bonded structure (every pair a rigid normal and
    /// tangential link), factorizes it once (sparse Cholesky) and condenses it to the contact
    /// zone: `R = [[Rnn, Rnt], [Rtn, Rtt]]`, the CLVs `R_c`, `R_v` and those of every load
    /// case.
    ///
    /// Errors: any [`FemError`] from [`Model::validate`], link placement problems, and
    /// [`FemError::Unstable`] naming the free DOFs when the bonded structure is a mechanism.
    pub fn condense(&self) -> Result<Condensed, FemError> {
        self.validate()?;
        let (asm, t_asm) = timed(|| assemble(self));
        let mut asm = asm?;
        let nnz_lower = asm.kii.as_ref().map_or(0, |k| k.compute_nnz());
        let (llt, t_fac) = timed(|| factorize(self, &asm));
        let (llt, lambda) = llt?;
        asm.kii_triplets = Vec::new();
        let kzz = std::mem::replace(&mut asm.kzz, Mat::zeros(0, 0));
        let kii = asm.kii.take();
        let (c, t_con) = timed(|| condense(&asm, kii.as_ref(), kzz, llt.as_ref(), lambda));
        drop(kii);
        let m = asm.map.m;
        let (case_rf, t_cases) = timed(|| case_vectors(&asm, &c.rf, llt.as_ref()));
        let t_con = t_con + t_cases;
        let block = |r0: usize, c0: usize| Mat::<f64>::from_fn(m, m, |i, j| c.r[(r0 + i, c0 + j)]);
        let clv = |g: usize| ContactLoadVector {
            normal: c.rf[g][..m].to_vec(),
            tangential: c.rf[g][m..].to_vec(),
        };
        let stats = CondensationStats {
            free_dofs: asm.map.n_i,
            pairs: m,
            prescribed_dofs: asm.map.n_p,
            nnz_lower,
            assembly_s: t_asm,
            factorization_s: t_fac,
            condensation_s: t_con,
            asymmetry: c.asymmetry,
            smallest_eigenvalue: lambda,
            round_off_zeroed: c.zeroed,
        };
        if c.r.col_iter().any(|col| col.iter().any(|v| !v.is_finite()))
            || c.rf.iter().flatten().any(|v| !v.is_finite())
            || case_rf.iter().flatten().any(|v| !v.is_finite())
        {
            return Err(FemError::LinearAlgebra(
                "non-finite contact stiffness (ill-conditioned bonded structure)".into(),
            ));
        }
        Ok(Condensed {
            rnn: block(0, 0),
            rnt: block(0, m),
            rtn: block(m, 0),
            rtt: block(m, m),
            constant: clv(0),
            variable: clv(1),
            case_names: self.cases.clone(),
            cases: case_rf
                .iter()
                .map(|rf| ContactLoadVector {
                    normal: rf[..m].to_vec(),
                    tangential: rf[m..].to_vec(),
                })
                .collect(),
            friction: self.pairs.iter().map(|p| p.friction).collect(),
            gap: self.pairs.iter().map(|p| p.gap).collect(),
            pair_names: (0..m).map(|i| self.pair_name(i)).collect(),
            normals: asm.map.nt.iter().map(|x| x.0).collect(),
            tangents: asm.map.nt.iter().map(|x| x.1).collect(),
            stats,
            model: self.clone(),
            asm,
            llt,
            element_k: Default::default(),
        })
    }
}

impl Condensed {
    /// The model this contact zone was condensed from.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Number of contact pairs.
    pub fn pairs(&self) -> usize {
        self.friction.len()
    }

    /// The resultant `[Fx, Fy]` of a load group's equivalent nodal loads (the variable group
    /// per unit `p`).
    pub fn load_resultant(&self, group: LoadGroup) -> [f64; 2] {
        let f = &self.asm.f_phys[match group {
            LoadGroup::Constant => 0,
            LoadGroup::Variable => 1,
        }];
        let mut r = [0.0; 2];
        for node in f.chunks_exact(3) {
            r[0] += node[0];
            r[1] += node[1];
        }
        r
    }

    /// The resultant `[Fx, Fy]` of a load case's equivalent nodal loads at factor 1.
    ///
    /// # Panics
    ///
    /// When `case` is not a case of the model.
    pub fn case_resultant(&self, case: CaseId) -> [f64; 2] {
        let f = &self.asm.cases[case.0].f_phys;
        let mut r = [0.0; 2];
        for node in f.chunks_exact(3) {
            r[0] += node[0];
            r[1] += node[1];
        }
        r
    }

    /// The bonded link values at the case factors `factors` (indexed like
    /// [`Condensed::case_names`]): every link at its undeformed length and
    /// `x = Σ factor·R_case`; `p` is set to `p`, a label for the results.
    ///
    /// # Panics
    ///
    /// When `factors` does not have one entry per case.
    pub fn bonded_at(&self, factors: &[f64], p: f64) -> LinkValues {
        assert_eq!(factors.len(), self.cases.len(), "one factor per load case");
        let m = self.pairs();
        let sum = |part: fn(&ContactLoadVector) -> &Vec<f64>| -> Vec<f64> {
            (0..m)
                .map(|i| {
                    self.cases
                        .iter()
                        .zip(factors)
                        .map(|(c, f)| f * part(c)[i])
                        .sum()
                })
                .collect()
        };
        LinkValues {
            p,
            x_n: sum(|c| &c.normal),
            x_t: sum(|c| &c.tangential),
            z_n: self.gap.clone(),
            z_t: vec![0.0; m],
        }
    }

    /// Moves the four blocks `Rnn`, `Rnt`, `Rtn`, `Rtt` out, leaving `0 × 0` matrices in their
    /// place: for a caller that hands them on whole (the structural analysis moves them into
    /// its contact zone, so that the `4m²` numbers are held once). Nothing else of the
    /// condensation reads them: recovery and [`Condensed::pairs`] work as before;
    /// [`Condensed::csm`] is then `0 × 0`.
    pub fn take_blocks(&mut self) -> [Mat<f64>; 4] {
        let take = |b: &mut Mat<f64>| std::mem::replace(b, Mat::new());
        [
            take(&mut self.rnn),
            take(&mut self.rnt),
            take(&mut self.rtn),
            take(&mut self.rtt),
        ]
    }

    /// The full contact stiffness matrix `[[Rnn, Rnt], [Rtn, Rtt]]` (2m × 2m); `0 × 0` when
    /// the blocks were taken ([`Condensed::take_blocks`]).
    pub fn csm(&self) -> Mat<f64> {
        let m = self.pairs();
        if self.rnn.nrows() != m {
            return Mat::new();
        }
        Mat::from_fn(2 * m, 2 * m, |i, j| match (i < m, j < m) {
            (true, true) => self.rnn[(i, j)],
            (true, false) => self.rnt[(i, j - m)],
            (false, true) => self.rtn[(i - m, j)],
            (false, false) => self.rtt[(i - m, j - m)],
        })
    }
}

/// The contact load vectors `R_F = K_zI K_II⁻¹ b_I − b_z` of every load case (normal entries,
/// then tangential). The cases `constant` and `variable` take the condensation's own vectors
/// (`group_rf`), so that they are the same bit for bit as [`Condensed::constant`] and
/// [`Condensed::variable`]; every other case is solved here, all in one solve, and an entry
/// is set to zero as round-off when it is below [`ROUND_OFF`] of the magnitude of the terms
/// that formed it (`|b_z|` and the products of `K_zI·x`).
fn case_vectors(
    asm: &Assembled,
    group_rf: &[Vec<f64>; 2],
    llt: Option<&Llt<usize, f64>>,
) -> Vec<Vec<f64>> {
    use faer::linalg::solvers::SolveCore;
    let nz = 2 * asm.map.m;
    let n_i = asm.map.n_i;
    let group_of = |c: usize| asm.group_case.iter().position(|g| *g == Some(c));
    let others: Vec<usize> = (0..asm.cases.len())
        .filter(|&c| group_of(c).is_none())
        .collect();
    let mut x = Mat::<f64>::from_fn(n_i, others.len(), |i, j| asm.cases[others[j]].b_i[i]);
    if let Some(llt) = llt {
        if !others.is_empty() {
            llt.solve_in_place_with_conj(faer::Conj::No, x.as_mut());
        }
    }
    (0..asm.cases.len())
        .map(|c| {
            if let Some(g) = group_of(c) {
                return group_rf[g].clone();
            }
            let j = others.iter().position(|&o| o == c).expect("listed");
            let b_z = &asm.cases[c].b_z;
            (0..nz)
                .map(|row| {
                    let col = &asm.kiz[row];
                    let xs = x.col_as_slice(j);
                    let (mut v, mut mag) = (-b_z[row], b_z[row].abs());
                    if llt.is_some() {
                        v += col.iter().map(|&(i, k)| k * xs[i]).sum::<f64>();
                        mag += col.iter().map(|&(i, k)| (k * xs[i]).abs()).sum::<f64>();
                    }
                    if v != 0.0 && v.abs() <= ROUND_OFF * mag {
                        0.0
                    } else {
                        v
                    }
                })
                .collect()
        })
        .collect()
}

/// Bytes of the dense matrices the condensation of `m` pairs with `n_i` free DOFs holds at
/// once: `K_zz` (becoming `R`, (2m)²), its four m×m blocks, and one chunk of solves
/// (`n_i × min(64, 2m)`). `None` when the count overflows.
pub fn dense_condensation_bytes(m: usize, n_i: usize) -> Option<u64> {
    let chunk = CHUNK.min(m.saturating_mul(2)) as u64;
    let m = m as u64;
    let doubles = m
        .checked_mul(m)?
        .checked_mul(8)?
        .checked_add((n_i as u64).checked_mul(chunk)?)?;
    doubles.checked_mul(8)
}

/// The memory of this machine in bytes (`MemTotal` of `/proc/meminfo`), `None` when it is not
/// known.
pub fn machine_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kb.checked_mul(1024)
}

/// Refuses a need of `bytes` (`None`: beyond any count) that this machine cannot hold, before
/// anything of that size is allocated. Where the machine's memory is unknown, the allocation
/// itself is tried without aborting.
pub fn check_memory(what: &str, bytes: Option<u64>) -> Result<(), FemError> {
    let too_large = |needed: Option<u64>, available: Option<u64>| FemError::TooLarge {
        what: what.to_string(),
        needed,
        available,
    };
    let Some(needed) = bytes else {
        return Err(too_large(None, machine_memory()));
    };
    match machine_memory() {
        Some(total) if needed > total => Err(too_large(Some(needed), Some(total))),
        Some(_) => Ok(()),
        None => {
            let mut probe: Vec<u8> = Vec::new();
            let len = usize::try_from(needed).map_err(|_| too_large(Some(needed), None))?;
            probe
                .try_reserve_exact(len)
                .map_err(|_| too_large(Some(needed), None))
        }
    }
}

/// Timings and sizes of a condensation.
#[derive(Debug, Clone, Default)]
pub struct CondensationStats {
    /// Number of free DOFs of the bonded structure (size of the factorized matrix).
    pub free_dofs: usize,
    /// Number of contact pairs `m`.
    pub pairs: usize,
    /// Number of prescribed (supported) DOFs.
    pub prescribed_dofs: usize,
    /// Stored entries of the lower triangle of the bonded stiffness.
    pub nnz_lower: usize,
    /// Seconds spent assembling (element matrices, triplets, CSC).
    pub assembly_s: f64,
    /// Seconds in the symbolic + numeric sparse Cholesky factorization and the stability check.
    pub factorization_s: f64,
    /// Seconds computing the Schur complement and the load vectors (2m + 2 solves).
    pub condensation_s: f64,
    /// Largest `|R − Rᵀ|` before symmetrization, relative to the largest `|R|`.
    pub asymmetry: f64,
    /// Estimate of the smallest eigenvalue of the Jacobi-scaled bonded stiffness (its inverse
    /// estimates the condition number; 1 when no DOF is free).
    pub smallest_eigenvalue: f64,
    /// Entries of `R` and of the contact load vectors that were round-off of an exact zero and
    /// were set to zero.
    pub round_off_zeroed: usize,
}

/// Times a closure.
pub(crate) fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let t = Instant::now();
    let v = f();
    (v, t.elapsed().as_secs_f64())
}
