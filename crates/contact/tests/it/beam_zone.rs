//! The generated beam on many frictional supports (`unilateral_oracle::fixtures::beam`) as a
//! contact zone. Shared by the tests, the benchmark and the `beam_path` example (they include
//! this file by its path).

use faer::Mat;
use unilateral_contact::ContactZone;
use unilateral_oracle::fixtures::beam;

/// [`beam::beam_on_supports`] as a [`ContactZone`].
pub fn beam_on_supports(m: usize, seed: u64) -> ContactZone {
    let b = beam::beam_on_supports(m, seed);
    let mat = |rows: &[Vec<f64>]| Mat::from_fn(m, m, |i, j| rows[i][j]);
    let mut zone = ContactZone::new(mat(&b.rnn), mat(&b.rtt));
    zone.friction = b.friction;
    zone.constant.normal = b.constant_normal;
    zone.variable.normal = b.variable_normal;
    zone.variable.tangential = b.variable_tangential;
    zone
}
