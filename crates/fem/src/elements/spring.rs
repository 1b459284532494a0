//! Linear springs between a node and the ground or another node: their stiffness and the
//! force they carry.

use super::ElemMat;
use crate::model::{Endpoint, Model, Spring, SpringKind};

/// Stiffness of a spring as an element matrix.
pub(crate) fn spring_matrix(s: &Spring) -> ElemMat {
    let b = s.b.0;
    match s.kind {
        SpringKind::Translational {
            direction,
            stiffness,
        } => {
            let d = unit(direction);
            let kd = [
                stiffness * d[0] * d[0],
                stiffness * d[0] * d[1],
                stiffness * d[1] * d[1],
            ];
            match s.a {
                Endpoint::Ground => ElemMat {
                    dofs: vec![3 * b, 3 * b + 1],
                    k: vec![kd[0], kd[1], kd[1], kd[2]],
                },
                Endpoint::Node(a) => {
                    let a = a.0;
                    let blk = [[kd[0], kd[1]], [kd[1], kd[2]]];
                    let mut k = vec![0.0; 16];
                    for i in 0..2 {
                        for j in 0..2 {
                            k[i * 4 + j] = blk[i][j];
                            k[(i + 2) * 4 + j + 2] = blk[i][j];
                            k[i * 4 + j + 2] = -blk[i][j];
                            k[(i + 2) * 4 + j] = -blk[i][j];
                        }
                    }
                    ElemMat {
                        dofs: vec![3 * a, 3 * a + 1, 3 * b, 3 * b + 1],
                        k,
                    }
                }
            }
        }
        SpringKind::Rotational { stiffness } => match s.a {
            Endpoint::Ground => ElemMat {
                dofs: vec![3 * b + 2],
                k: vec![stiffness],
            },
            Endpoint::Node(a) => ElemMat {
                dofs: vec![3 * a.0 + 2, 3 * b + 2],
                k: vec![stiffness, -stiffness, -stiffness, stiffness],
            },
        },
    }
}

/// The force (tension, elongation positive) or moment of a spring for the physical
/// displacements `u`; adds the force the spring exerts on the structure from the ground (none
/// between two nodes but a couple) to `ground` (`[Fx, Fy, M about the origin]`).
/// The unit direction of a translational spring (`[0, 0]` for a rotational one): what
/// [`spring_force`] takes, kept by a structure recovered at every frame of a path.
pub(crate) fn spring_direction(sp: &Spring) -> [f64; 2] {
    match sp.kind {
        SpringKind::Translational { direction, .. } => unit(direction),
        SpringKind::Rotational { .. } => [0.0; 2],
    }
}

/// The force of spring `sp` (along its unit direction `d`, [`spring_direction`]) under the
/// displacements `u`; adds the spring's forces on the ground to `ground`.
pub(crate) fn spring_force(
    model: &Model,
    sp: &Spring,
    d: [f64; 2],
    u: &[f64],
    ground: &mut [f64; 3],
) -> f64 {
    let ua = |d: usize| match sp.a {
        Endpoint::Ground => 0.0,
        Endpoint::Node(a) => u[3 * a.0 + d],
    };
    let b = sp.b.0;
    let pos = model.nodes[b];
    match sp.kind {
        SpringKind::Translational { stiffness, .. } => {
            let e = d[0] * (u[3 * b] - ua(0)) + d[1] * (u[3 * b + 1] - ua(1));
            let force = stiffness * e;
            let fb = [-force * d[0], -force * d[1]];
            ground[0] += fb[0];
            ground[1] += fb[1];
            ground[2] += pos[0] * fb[1] - pos[1] * fb[0];
            if let Endpoint::Node(a) = sp.a {
                let pa = model.nodes[a.0];
                ground[0] -= fb[0];
                ground[1] -= fb[1];
                ground[2] -= pa[0] * fb[1] - pa[1] * fb[0];
            }
            force
        }
        SpringKind::Rotational { stiffness } => {
            let mo = stiffness * (u[3 * b + 2] - ua(2));
            if sp.a == Endpoint::Ground {
                ground[2] -= mo;
            }
            mo
        }
    }
}

fn unit(v: [f64; 2]) -> [f64; 2] {
    let l = v[0].hypot(v[1]);
    [v[0] / l, v[1] / l]
}
