//! Normalisation of a contact zone by a force scale and a stiffness scale.
//!
//! The answer of a contact problem may not depend on the units the engineer types (N and m,
//! kN and mm, MN and m). The zone's numbers carry two independent units: forces (`R_c`, `R_v`,
//! the tightening `c`, and the LCP's `x`) and displacements (gaps, the LCP's `z`); stiffness is
//! force over displacement. The solve therefore divides
//!
//! * every stiffness by `S = 2^k_s`, a power of two near the largest entry of the four blocks,
//! * every force by `F = 2^k_f`, a power of two near the largest force the data produce (the
//!   loads, the tightening and the gap forces `R·η`),
//! * every displacement by `F/S`,
//!
//! so that the LCP the engine sees has stiffness and loads of order one, whatever the units. The
//! scales are exact powers of two, taken from the binary exponents: a change of units by `2^j`
//! changes the normalised data by nothing at all (not one bit), and any other change of units
//! changes them by one rounding per number — which is how the same states and events come out
//! for `W = 1e-150` and `W = 1e150`. Forces and displacements that would be out of range in the
//! user's units (`1e308 · 2`) are formed only at the very end, where they are checked.
//!
//! The exponents of products (`R·η`) are added as integers, never multiplied as numbers, so no
//! scale overflows or underflows on the way.

use faer::Mat;

use crate::zone::{max_abs, roundoff_of_zero};
use crate::{ContactLoad, ContactZone};

pub(crate) use unilateral_lcp::binary::{exponent, ldexp};

fn max_exp<'a>(v: impl IntoIterator<Item = &'a f64>) -> Option<i32> {
    v.into_iter().filter_map(|&x| exponent(x)).max()
}

/// The scales of a zone: forces `2^force`, stiffness `2^stiffness`, displacements
/// `2^(force − stiffness)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Units {
    pub force: i32,
    pub stiffness: i32,
    /// The force exponent of the data alone, without the tightening (`force` with `c = 0`).
    pub data_force: i32,
}

impl Units {
    /// The scales of `zone` solved with tightening `c` (a force).
    pub fn of(zone: &ContactZone, c: f64) -> Self {
        let m = zone.pairs();
        let mat_exp = |mat: &Mat<f64>| exponent(max_abs(mat));
        let stiffness = [&zone.rnn, &zone.rnt, &zone.rtn, &zone.rtt]
            .iter()
            .filter_map(|mm| mat_exp(mm))
            .max()
            .unwrap_or(0);
        let loads = [
            &zone.constant.normal,
            &zone.constant.tangential,
            &zone.variable.normal,
            &zone.variable.tangential,
        ];
        let mut force = loads.iter().filter_map(|v| max_exp(v.iter())).max();
        // The gap forces R·η: exponent of the column's largest stiffness plus the gap's, plus
        // one for the rounding up of both mantissas.
        for j in 0..m {
            if let Some(eg) = exponent(zone.gap[j]) {
                let col = (0..m)
                    .flat_map(|i| [zone.rnn[(i, j)], zone.rtn[(i, j)]])
                    .fold(0.0f64, |a, b| a.max(b.abs()));
                if let Some(ec) = exponent(col) {
                    force = force.max(Some(ec + eg + 1));
                }
            }
        }
        Self {
            force: force.max(exponent(c)).unwrap_or(stiffness),
            stiffness,
            data_force: force.unwrap_or(stiffness),
        }
    }

    fn displacement(&self) -> i32 {
        self.force - self.stiffness
    }

    /// A force in the user's units → normalised.
    pub fn normalised_force(&self, f: f64) -> f64 {
        ldexp(f, -self.force)
    }

    /// A normalised force → the user's units.
    pub fn user_force(&self, f: f64) -> f64 {
        ldexp(f, self.force)
    }

    /// A normalised displacement → the user's units.
    pub fn user_displacement(&self, z: f64) -> f64 {
        ldexp(z, self.displacement())
    }

    /// A normalised stiffness → the user's units.
    pub fn user_stiffness(&self, k: f64) -> f64 {
        ldexp(k, self.stiffness)
    }

    /// The sparse zone in the same normalised units as [`Units::normalise`]'s zone: the
    /// stiffness blocks by the stiffness scale, the loads by the force scale, the gaps by the
    /// displacement scale (so that `R` and `R_F` formed from it are the normalised zone's).
    pub fn normalise_sparse(&self, zone: &crate::SparseZone) -> crate::SparseZone {
        let mut z = zone.clone();
        for k in [&mut z.kii, &mut z.kiz, &mut z.kzz] {
            k.val_mut()
                .iter_mut()
                .for_each(|v| *v = ldexp(*v, -self.stiffness));
        }
        for v in z
            .constant
            .iter_mut()
            .chain(z.variable.iter_mut())
            .chain(z.cases.iter_mut().flatten())
            .flatten()
        {
            *v = self.normalised_force(*v);
        }
        z.gap
            .iter_mut()
            .for_each(|g| *g = ldexp(*g, -self.displacement()));
        z
    }

    /// The normalised zone. Diagonal entries of `Rnn` and `Rtt` that lie below zero only by
    /// round-off of the zone's scale (see [`roundoff_of_zero`]) are set to zero.
    pub fn normalise(&self, zone: &ContactZone) -> ContactZone {
        let m = zone.pairs();
        let scale = zone.stiffness_scale();
        let stiff = |mat: &Mat<f64>, clamp: bool| {
            Mat::<f64>::from_fn(m, m, |i, j| {
                let v = mat[(i, j)];
                if clamp && i == j && v < 0.0 && v >= -roundoff_of_zero(scale, m) {
                    0.0
                } else {
                    ldexp(v, -self.stiffness)
                }
            })
        };
        let forces = |v: &[f64]| {
            v.iter()
                .map(|&x| self.normalised_force(x))
                .collect::<Vec<_>>()
        };
        let load = |l: &ContactLoad| ContactLoad {
            normal: forces(&l.normal),
            tangential: forces(&l.tangential),
        };
        ContactZone {
            rnn: stiff(&zone.rnn, true),
            rnt: stiff(&zone.rnt, false),
            rtn: stiff(&zone.rtn, false),
            rtt: stiff(&zone.rtt, true),
            friction: zone.friction.clone(),
            gap: zone
                .gap
                .iter()
                .map(|&g| ldexp(g, -self.displacement()))
                .collect(),
            constant: load(&zone.constant),
            variable: load(&zone.variable),
            cases: zone
                .cases
                .iter()
                .map(|c| crate::LoadCase {
                    name: c.name.clone(),
                    load: load(&c.load),
                })
                .collect(),
            pair_names: zone.pair_names.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: the IEEE 754 binary64 layout (2^e exactly, subnormals down to 2^-1074).
    #[test]
    fn exponents_and_powers_of_two_are_exact() {
        for e in [-1074, -1060, -1022, -1, 0, 1, 52, 1023] {
            let x = ldexp(1.0, e);
            assert_eq!(exponent(x), Some(e), "2^{e}");
            if e > -1074 {
                assert_eq!(exponent(x * 1.5), Some(e), "1.5 · 2^{e}");
            }
            assert_eq!(ldexp(x, -e), 1.0, "2^{e} · 2^{}", -e);
        }
        assert_eq!(exponent(0.0), None);
        assert_eq!(exponent(f64::NAN), None);
        assert_eq!(exponent(-3.0), Some(1));
    }

    /// The parts of a zone, by hand: six pairs, 0–2 chained through `R_nn` (0, 1) and a single
    /// entry of `R_tn` (1 → 2, one direction only), 3 and 5 through `R_nt` (5 → 3), 4 alone
    /// with a diagonal only. Numbered by their first pair.
    #[test]
    fn parts_are_the_pairs_that_stiffness_joins_directly_or_through_others() {
        let m = 6;
        let diag = Mat::from_fn(m, m, |i, j| if i == j { 1.0 } else { 0.0 });
        let mut zone = ContactZone::new(diag.clone(), diag);
        zone.rnn[(0, 1)] = -0.5;
        zone.rnn[(1, 0)] = -0.5;
        zone.rtn[(2, 1)] = 1e-300;
        zone.rnt[(5, 3)] = 2.0;
        assert_eq!(components(&zone), [0, 0, 0, 1, 2, 1]);
        // No coupling at all: every pair its own part; a full matrix: one part.
        let alone = ContactZone::new(Mat::identity(m, m), Mat::identity(m, m));
        assert_eq!(components(&alone), [0, 1, 2, 3, 4, 5]);
        let full = ContactZone::new(Mat::from_fn(m, m, |_, _| 1.0), Mat::identity(m, m));
        assert_eq!(components(&full), [0; 6]);
    }
}

/// The force scales of a (normalised) zone without the tightening: the constant load of a row
/// with the gap forces `R·η` it carries (as the LCP sums them: a row whose terms cancel to
/// round-off, the gaps a rigid motion closes, carries none — its terms' sizes would make a
/// pair's real force of a small load read as round-off), and the variable load, each pair's
/// own, normal and tangential (its forces' scales; the largest of its part of the zone, its
/// displacements' scale), and the parts of the zone ([`components`]).
pub(crate) fn load_scales(zone: &ContactZone) -> DataForce {
    let m = zone.pairs();
    let (q0, _) = crate::lcp::load_vectors(zone);
    // the rows are [n; f·n + t; f·n − t]: the tangential part is half their difference
    let row = |i: usize, normal: bool| {
        let (c, v) = if normal {
            (&zone.constant.normal, &zone.variable.normal)
        } else {
            (&zone.constant.tangential, &zone.variable.tangential)
        };
        RowLoads {
            constant: if normal {
                q0[i].abs()
            } else {
                ((q0[m + i] - q0[2 * m + i]) / 2.0).abs()
            },
            loads: c[i].abs(),
            variable: v[i].abs(),
        }
    };
    let pairs: Vec<PairLoads> = (0..m)
        .map(|i| PairLoads {
            normal: row(i, true),
            tangential: row(i, false),
        })
        .collect();
    DataForce {
        pairs,
        component: components(zone),
        friction: zone.friction.clone(),
    }
}

/// The parts of a zone that do not act on each other, as a part's number for each pair: pairs
/// `i` and `j` are in one part where a stiffness couples them (an entry of `R_nn`, `R_nt`,
/// `R_tn` or `R_tt` at `(i, j)` or `(j, i)`), directly or through other pairs. Parts are
/// numbered by their first pair, in order. Round-off of one part's values is no scale of
/// another's: two structures in one model, one carrying forces of 1e9 N, the other 400 N.
pub(crate) fn components(zone: &ContactZone) -> Vec<usize> {
    let m = zone.pairs();
    let mut parent: Vec<usize> = (0..m).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let coupled = |i: usize, j: usize| {
        [&zone.rnn, &zone.rnt, &zone.rtn, &zone.rtt]
            .iter()
            .any(|r| r[(i, j)] != 0.0 || r[(j, i)] != 0.0)
    };
    for i in 0..m {
        for j in i + 1..m {
            if coupled(i, j) {
                let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                if a != b {
                    parent[a.max(b)] = a.min(b);
                }
            }
        }
    }
    let mut number = vec![usize::MAX; m];
    let mut next = 0;
    (0..m)
        .map(|i| {
            let r = root(&mut parent, i);
            if number[r] == usize::MAX {
                number[r] = next;
                next += 1;
            }
            number[r]
        })
        .collect()
}

/// The largest of `value(i)` over the pairs `i` of each part of the zone (`part` numbers them
/// as [`components`] does), and at least `floor`: the scales a pair's round-off is judged
/// against in its own part.
pub(crate) fn largest_by_part(
    part: &[usize],
    floor: f64,
    value: impl Fn(usize) -> f64,
) -> Vec<f64> {
    let mut largest = vec![floor; part.iter().max().map_or(0, |&c| c + 1)];
    for (i, &c) in part.iter().enumerate() {
        largest[c] = largest[c].max(value(i));
    }
    largest
}

/// The force scales of the data without the tightening ([`load_scales`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct DataForce {
    /// Each pair's own loads.
    pub pairs: Vec<PairLoads>,
    /// The part of the zone each pair belongs to ([`components`]).
    pub component: Vec<usize>,
    /// Each pair's friction coefficient: where `f·x_n` is zero the friction law allows no
    /// tangential force at all.
    pub friction: Vec<f64>,
}

/// The loads of one pair ([`load_scales`]): its normal row's and its tangential link's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PairLoads {
    pub normal: RowLoads,
    pub tangential: RowLoads,
}

/// The loads of one row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct RowLoads {
    /// The constant load with the gap forces.
    pub constant: f64,
    /// The constant load alone.
    pub loads: f64,
    /// The variable load at p = 1.
    pub variable: f64,
}

impl RowLoads {
    /// The scale of the row's force at `p`: its loads, and the gap forces' round-off
    /// ([`GAP_FORCE_SHARE`]).
    fn at(&self, p: f64) -> f64 {
        self.loads
            .max(p.abs() * self.variable)
            .max(GAP_FORCE_SHARE * self.constant)
    }
}

/// The share of the gap forces in the scale the states' forces are judged against: their
/// round-off is about 1e-16 of them times the conditioning, which 1e-4 × the states' margin
/// (1e-9) covers up to 1e3; a full share would read a stopper's 3 N beside gap forces of 1e10
/// (1000 m × 1e7 N/m) as round-off, the stopper "open" while it carries the push.
const GAP_FORCE_SHARE: f64 = 1e-4;

impl DataForce {
    /// The scale of the displacements a point at `p` carries (the gaps' own size in it: its
    /// force equivalent, the gap forces): the largest constant load with the gap forces and
    /// variable load of a row of the zone. The zone's, not a part's ([`components`]): in the
    /// normalised units a part's loads are no measure of its displacements (a flexible beam
    /// beside a stiff one), and on the paper's Example 1 zone beside two pairs of any size
    /// (`a_zone_of_two_parts_that_do_not_touch_gives_each_its_own_answer`) the zone's is right.
    pub fn at(&self, p: f64) -> f64 {
        self.pairs.iter().fold(0.0f64, |a, l| {
            [&l.normal, &l.tangential]
                .iter()
                .fold(a, |a, r| a.max(r.constant).max(p.abs() * r.variable))
        })
    }

    /// The scales each pair's forces at `p` are judged against, `(normal, tangential)`: the
    /// loads of the pair's own rows ([`RowLoads::at`]); the tangential force, the half
    /// difference of the friction rows `f·x_n ± x_t`, takes both. Not the zone's largest load:
    /// a push of 1e12 that only slides a frictionless pair is no normal force of any pair, and
    /// their compression of 400 beside `1e-9·1e12` read "open".
    pub fn forces_at(&self, p: f64) -> Vec<(f64, f64)> {
        self.pairs
            .iter()
            .map(|l| {
                let n = l.normal.at(p);
                (n, n.max(l.tangential.at(p)))
            })
            .collect()
    }
}
