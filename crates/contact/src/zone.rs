//! The contact zone: the data of `formulation.md` §2, as a finite-element program hands it over.

use faer::Mat;

use crate::{ContactError, LoadCase};

/// Contact load vector (CLV) of one load group: link forces of the bonded structure,
/// compression positive, one entry per contact pair.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ContactLoad {
    /// Forces in the normal links (`R_n`), compression positive.
    pub normal: Vec<f64>,
    /// Forces in the tangential links (`R_t`), the paper's sign convention (clockwise couple positive).
    pub tangential: Vec<f64>,
}

impl ContactLoad {
    /// A zero load on `m` pairs.
    pub fn zeros(m: usize) -> Self {
        Self {
            normal: vec![0.0; m],
            tangential: vec![0.0; m],
        }
    }
}

/// The contact zone of a structure with `m` contact pairs.
///
/// Matrix blocks follow `formulation.md` §2: the first index is the link whose force is read,
/// the second the link that is dislocated. `rnn` and `rtt` are symmetric positive semidefinite.
#[derive(Debug, Clone)]
pub struct ContactZone {
    /// Normal–normal contact stiffness (`m × m`).
    pub rnn: Mat<f64>,
    /// Normal force from tangential dislocation (`m × m`).
    pub rnt: Mat<f64>,
    /// Tangential force from normal dislocation (`m × m`).
    pub rtn: Mat<f64>,
    /// Tangential–tangential contact stiffness (`m × m`).
    pub rtt: Mat<f64>,
    /// Coulomb friction coefficient per pair, `f ≥ 0`.
    pub friction: Vec<f64>,
    /// Initial gap per pair, `η ≥ 0`.
    pub gap: Vec<f64>,
    /// Constant (dead) load part `R_c`.
    pub constant: ContactLoad,
    /// Variable load part `R_v`, multiplied by the load parameter `p`.
    pub variable: ContactLoad,
    /// Every load case by name, in the order of the file or the model (`constant` and
    /// `variable` among them when the problem has them): what a load history's stages
    /// multiply by their factors. The paper's method reads `constant` and `variable` only.
    pub cases: Vec<LoadCase>,
    /// Display names of the pairs (default `"1"`, `"2"`, …).
    pub pair_names: Vec<String>,
}

impl ContactZone {
    /// A frictionless, load-free zone with the given normal stiffness and zero coupling blocks
    /// (and no load cases).
    pub fn new(rnn: Mat<f64>, rtt: Mat<f64>) -> Self {
        let m = rnn.nrows();
        Self {
            rnt: Mat::zeros(m, m),
            rtn: Mat::zeros(m, m),
            rnn,
            rtt,
            friction: vec![0.0; m],
            gap: vec![0.0; m],
            constant: ContactLoad::zeros(m),
            variable: ContactLoad::zeros(m),
            cases: Vec::new(),
            pair_names: (1..=m).map(|i| i.to_string()).collect(),
        }
    }

    /// Number of contact pairs `m`.
    pub fn pairs(&self) -> usize {
        self.rnn.nrows()
    }

    /// No constant load and no initial gap: the problem without the tightening is
    /// homogeneous (`q0 = 0`), a state at `p > 0` scaled by `s > 0` being the state at `s·p`.
    pub fn is_homogeneous(&self) -> bool {
        self.constant.normal.iter().all(|&v| v == 0.0)
            && self.constant.tangential.iter().all(|&v| v == 0.0)
            && self.gap.iter().all(|&g| g == 0.0)
    }

    /// Checks sizes, finiteness, signs and the symmetry of `Rnn` and `Rtt`, and the size and
    /// finiteness of every load case (`load.NAME.normal`, `load.NAME.tangential`).
    ///
    /// Symmetry is checked relative to the largest entry of the matrix (`1e-8`), since matrices
    /// computed by other programs carry round-off.
    pub fn validate(&self) -> Result<(), ContactError> {
        let m = self.rnn.nrows();
        if m == 0 {
            return Err(ContactError::Empty);
        }
        for (name, mat) in [
            ("Rnn", &self.rnn),
            ("Rnt", &self.rnt),
            ("Rtn", &self.rtn),
            ("Rtt", &self.rtt),
        ] {
            if mat.nrows() != m || mat.ncols() != m {
                return Err(ContactError::MatrixSize {
                    name,
                    rows: mat.nrows(),
                    cols: mat.ncols(),
                    pairs: m,
                });
            }
            for j in 0..m {
                for i in 0..m {
                    let v = mat[(i, j)];
                    if !v.is_finite() {
                        return Err(ContactError::NotFinite {
                            name: name.to_string(),
                            index: format!("({}, {})", i + 1, j + 1),
                        });
                    }
                }
            }
        }
        let zone_scale = self.stiffness_scale();
        for (name, mat) in [("Rnn", &self.rnn), ("Rtt", &self.rtt)] {
            let scale = max_abs(mat);
            for j in 0..m {
                for i in 0..j {
                    let (a, b) = (mat[(i, j)], mat[(j, i)]);
                    if (a - b).abs() > 1e-8 * scale {
                        return Err(ContactError::NotSymmetric {
                            name,
                            row: i + 1,
                            col: j + 1,
                            upper: a,
                            lower: b,
                        });
                    }
                }
            }
            for i in 0..m {
                if mat[(i, i)] < -roundoff_of_zero(zone_scale, m) {
                    return Err(ContactError::NegativeDiagonal {
                        name,
                        pair: i + 1,
                        value: mat[(i, i)],
                    });
                }
            }
        }
        let vectors: [(&str, &Vec<f64>); 6] = [
            ("friction", &self.friction),
            ("gap", &self.gap),
            ("load.constant.normal", &self.constant.normal),
            ("load.constant.tangential", &self.constant.tangential),
            ("load.variable.normal", &self.variable.normal),
            ("load.variable.tangential", &self.variable.tangential),
        ];
        for (name, v) in vectors {
            if v.len() != m {
                return Err(ContactError::VectorSize {
                    name: name.to_string(),
                    len: v.len(),
                    pairs: m,
                });
            }
            if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                return Err(ContactError::NotFinite {
                    name: name.to_string(),
                    index: format!("[{}]", i + 1),
                });
            }
        }
        for case in &self.cases {
            for (part, v) in [
                ("normal", &case.load.normal),
                ("tangential", &case.load.tangential),
            ] {
                let name = format!("load.{}.{part}", case.name);
                if v.len() != m {
                    return Err(ContactError::VectorSize {
                        name,
                        len: v.len(),
                        pairs: m,
                    });
                }
                if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                    return Err(ContactError::NotFinite {
                        name,
                        index: format!("[{}]", i + 1),
                    });
                }
            }
        }
        if let Some(i) = self.friction.iter().position(|&f| f < 0.0) {
            return Err(ContactError::Negative {
                name: "friction",
                pair: i + 1,
                value: self.friction[i],
            });
        }
        if let Some(i) = self.gap.iter().position(|&g| g < 0.0) {
            return Err(ContactError::Negative {
                name: "gap",
                pair: i + 1,
                value: self.gap[i],
            });
        }
        if self.pair_names.len() != m {
            return Err(ContactError::VectorSize {
                name: "pair_names".to_string(),
                len: self.pair_names.len(),
                pairs: m,
            });
        }
        Ok(())
    }
}

impl ContactZone {
    /// Checks that `Rnn` and `Rtt` are positive semidefinite, as a stiffness is (after
    /// [`ContactZone::validate`], which checks their symmetry and diagonals), up to
    /// `SEMIDEFINITE_SLACK` of the zone's largest entry: for matrices a user gives, where a
    /// wrong sign or a swapped entry makes a zone no structure has (a negative eigenvalue of
    /// the size of the entries), while a zone condensed from a finely meshed structure — whose
    /// zero eigenvalues carry the condensation's round-off — passes. Each block `R + δI` must
    /// admit a Cholesky factorisation; the first pair of pairs whose 2 × 2 block is not
    /// semidefinite is named first (`R_ii R_jj < R_ij²`), the commonest mistake. Relative to
    /// the data, so the same in every unit system. `O(m³)`: the zone the program condenses
    /// from a structure is not checked this way.
    pub fn check_semidefinite(&self) -> Result<(), ContactError> {
        let m = self.rnn.nrows();
        let delta = SEMIDEFINITE_SLACK * self.stiffness_scale();
        for (name, mat) in [("Rnn", &self.rnn), ("Rtt", &self.rtt)] {
            // Symmetric to round-off (checked by `validate`): the upper triangle for the
            // pairs, the lower one for the factorisation, each read down its columns.
            let d = |i: usize| mat[(i, i)] + delta;
            for j in 0..m {
                for i in 0..j {
                    let r = mat[(i, j)];
                    if d(i) * d(j) < r * r {
                        return Err(ContactError::NotSemidefinite {
                            name,
                            row: i + 1,
                            col: j + 1,
                            why: format!(
                                "pairs {} and {} have {name}({0},{0})·{name}({1},{1}) = {} < {name}({0},{1})² = {}",
                                i + 1,
                                j + 1,
                                mat[(i, i)] * mat[(j, j)],
                                r * r
                            ),
                        });
                    }
                }
            }
            let mut shifted = mat.clone();
            for i in 0..m {
                shifted[(i, i)] += delta;
            }
            if let Err(faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index }) =
                shifted.llt(faer::Side::Lower)
            {
                let k = index + 1;
                return Err(ContactError::NotSemidefinite {
                    name,
                    row: k,
                    col: k,
                    why: format!(
                        "its rows and columns of pairs 1 to {k} make a matrix with a negative eigenvalue (a Cholesky factorisation breaks down at pair {k})"
                    ),
                });
            }
        }
        Ok(())
    }

    /// The largest entry of the four stiffness blocks: the scale against which round-off of the
    /// stiffness is measured.
    pub(crate) fn stiffness_scale(&self) -> f64 {
        [&self.rnn, &self.rnt, &self.rtn, &self.rtt]
            .iter()
            .map(|m| max_abs(m))
            .fold(0.0f64, f64::max)
    }
}

/// How far below zero (relative to the zone's largest entry) an eigenvalue of a user's `Rnn` or
/// `Rtt` may lie ([`ContactZone::check_semidefinite`]). The zone `unilateral zone` writes for
/// Example 1's beam with 2000 elements a span (`E·I = 1`, elements 1 mm long) has an `Rnn`
/// eigenvalue of −2.7e-4 of its largest entry — the condensation's round-off at a condition
/// number near 1e13 — and is solved like the model; a typed mistake gives one of the order of
/// the entries.
pub(crate) const SEMIDEFINITE_SLACK: f64 = 1e-3;

/// How far below zero a diagonal entry of `Rnn` or `Rtt` may lie and still be round-off of a
/// zero stiffness (a support that the rest of the structure does not hold in that direction,
/// e.g. a statically determinate one). The contact stiffness is a condensed (Schur complement)
/// stiffness: its entries carry round-off of the order `ε·κ·‖K‖` of the structure's own
/// stiffness, far above `ε·‖R‖` when the structure is finely meshed. `1e-10·m` of the zone's
/// largest stiffness admits that round-off for condition numbers up to about `1e5` per pair,
/// while any negative stiffness that a user writes is many orders larger. It is relative to the
/// zone's scale (all four blocks), never absolute, so it means the same in every unit system.
pub(crate) fn roundoff_of_zero(scale: f64, m: usize) -> f64 {
    1e-10 * m as f64 * scale
}

pub(crate) fn max_abs(mat: &Mat<f64>) -> f64 {
    let mut s = 0.0f64;
    for j in 0..mat.ncols() {
        for i in 0..mat.nrows() {
            s = s.max(mat[(i, j)].abs());
        }
    }
    s
}
