//! The stability of the bonded structure: its sparse Cholesky factorization, the estimate of
//! its smallest eigenvalue, and the diagnosis of a small one as a mechanism (naming the DOFs
//! that move) or as ill-conditioning of a stable structure.

use crate::assemble::Assembled;
use crate::dofs::DofMap;
use crate::elements::spring::spring_matrix;
use crate::elements::{element_stiffness, ElemMat};
use crate::error::{DofLabel, FemError, FreeDof};
use crate::model::{Model, NodeId};
use faer::linalg::solvers::SolveCore;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Conj, Mat, Side};

/// A deterministic pseudo-random vector in (−1, 1).
fn pseudo_random(n: usize) -> Vec<f64> {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..n)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        })
        .collect()
}

/// Inverse iteration on the Jacobi-scaled matrix. Returns (eigenvalue estimate, mode in
/// unscaled coordinates).
///
/// At least `min_iters` iterations; then, up to `max_iters`, until the eigenvalue estimate
/// changes by less than 1e-6 of itself from one iteration to the next. The components of the
/// mode along the second eigenvector shrink by `λ₁/λ₂` per iteration, which for the lowest
/// modes of a fine mesh is only about 1/16 (the eigenvalues of a beam grow as k⁴): the few
/// iterations that estimate `λ` well are not always enough for the mode itself, which the
/// mechanism test reads.
fn inverse_iteration(
    llt: &Llt<usize, f64>,
    diag: &[f64],
    min_iters: usize,
    max_iters: usize,
) -> (f64, Vec<f64>) {
    let n = diag.len();
    let sq: Vec<f64> = diag
        .iter()
        .map(|d| d.abs().max(f64::MIN_POSITIVE).sqrt())
        .collect();
    let mut v = pseudo_random(n);
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let nv = norm(&v);
    v.iter_mut().for_each(|x| *x /= nv);
    let mut lambda = f64::INFINITY;
    for it in 0..max_iters {
        // A = D^{-1/2} K D^{-1/2}, so A⁻¹ v = D^{1/2} K⁻¹ D^{1/2} v.
        let mut w = Mat::<f64>::from_fn(n, 1, |i, _| v[i] * sq[i]);
        llt.solve_in_place_with_conj(Conj::No, w.as_mut());
        let wv: Vec<f64> = (0..n).map(|i| w[(i, 0)] * sq[i]).collect();
        let nw = norm(&wv);
        if !nw.is_finite() || nw == 0.0 {
            return (0.0, v.iter().zip(&sq).map(|(a, s)| a / s).collect());
        }
        let previous = lambda;
        lambda = 1.0 / nw;
        v = wv.iter().map(|x| x / nw).collect();
        if it + 1 >= min_iters && (previous - lambda).abs() <= 1e-6 * lambda {
            break;
        }
    }
    (lambda, v.iter().zip(&sq).map(|(a, s)| a / s).collect())
}

/// Threshold on the smallest eigenvalue of the Jacobi-scaled bonded stiffness below which the
/// mode is examined by [`element_force_ratio`]; above it the structure is stable.
const SINGULAR_EIG: f64 = 1e-13;

/// Threshold on [`element_force_ratio`] below which a mode of small eigenvalue is a mechanism.
///
/// A mechanism moves every element and spring rigidly, so the exact ratio is zero and the
/// computed one is round-off: 1e-16 for a few elements; for a member of `N` elements the
/// factorization mixes the null mode with the lowest deforming modes, and the least deforming
/// combination of six vectors of block inverse iteration still leaves 2e-14 (N = 1000),
/// 3e-13 (5000), 5e-12 (20000), 1e-10 (2×50000, a hinge chain). The lowest mode of a stable
/// member is smooth: an element of length `h` on a span `L` carries forces of relative size
/// ≈ (πh/L)²/25 (1.4e-8 for a pinned–pinned beam of 5000 elements, 3.7e-11 for 10⁵), and only
/// their assembly cancels further, to the eigenvalue ≈ (πh/L)⁴/12. The threshold separates the
/// two up to 10⁵ elements per member for a stable member (never a false mechanism) and to
/// 2·10⁴ for a mechanism (above, it is reported as ill-conditioned, which it also is).
const MECHANISM_RATIO: f64 = 1e-11;

/// The physical displacements (3 per node) of a free-DOF vector with `z = 0` and `s = 0`.
fn physical_mode(map: &DofMap, mode: &[f64]) -> Vec<f64> {
    map.rows
        .iter()
        .map(|r| {
            r.iter()
                .filter(|(g, _)| *g < map.n_i)
                .map(|(g, c)| c * mode[*g])
                .sum()
        })
        .collect()
}

/// How far a displacement field is from moving every element and spring rigidly:
///
/// `ρ = Σ_e ‖k̃_e ũ_e‖ / Σ_e ‖k̃_e‖·‖ũ_e‖`, with each element's (or spring's) matrix and
/// displacements scaled by its own diagonal `D_e` (`k̃_e = D_e^{-1/2} k_e D_e^{-1/2}`,
/// `ũ_e = D_e^{1/2} u_e`, DOFs with a zero diagonal left out, `‖k̃_e‖` the Frobenius norm).
///
/// The scaling makes `ρ` independent of units and of the mix of translations and rotations.
/// The element forces are computed before assembly, so they are not lost in the cancellation
/// that makes the assembled `K u` of a smooth mode of a fine mesh as small as round-off:
/// `ρ` is ≈ 1e-16 for a rigid motion of every element (a mechanism), and of order (h/L)²
/// for the smooth lowest mode of a stable member divided into elements of length `h`.
fn element_force_ratio(model: &Model, phys: &[f64]) -> f64 {
    let mut num = 0.0;
    let mut den = 0.0;
    let mut add = |em: &ElemMat| {
        let n = em.dofs.len();
        let d: Vec<f64> = (0..n).map(|a| em.k[a * n + a]).collect();
        let live: Vec<usize> = (0..n).filter(|&a| d[a] > 0.0).collect();
        let sq: Vec<f64> = d.iter().map(|x| x.max(0.0).sqrt()).collect();
        let mut force2 = 0.0;
        let mut kn2 = 0.0;
        let mut un2 = 0.0;
        for &a in &live {
            let mut f = 0.0;
            for &b in &live {
                let kab = em.k[a * n + b] / (sq[a] * sq[b]);
                kn2 += kab * kab;
                f += kab * sq[b] * phys[em.dofs[b]];
            }
            force2 += f * f;
            let u = sq[a] * phys[em.dofs[a]];
            un2 += u * u;
        }
        num += force2.sqrt();
        den += kn2.sqrt() * un2.sqrt();
    };
    for el in &model.elements {
        add(&element_stiffness(model, el));
    }
    for sp in &model.springs {
        add(&spring_matrix(sp));
    }
    if den > 0.0 {
        num / den
    } else {
        0.0
    }
}

fn free_dofs_from_mode(map: &DofMap, mode: &[f64]) -> Vec<FreeDof> {
    // physical displacement of the mode (z = 0, s = 0)
    let phys = physical_mode(map, mode);
    let max = phys.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let mut out = Vec::new();
    if max == 0.0 {
        return out;
    }
    for (d, v) in phys.iter().enumerate() {
        if v.abs() > 1e-3 * max {
            out.push(FreeDof {
                node: NodeId(d / 3),
                dof: [DofLabel::Ux, DofLabel::Uy, DofLabel::Rz][d % 3],
                amplitude: v / max,
            });
        }
    }
    out
}

/// Number of vectors of the block inverse iteration that looks for a mechanism mode.
const BLOCK: usize = 6;

/// Block inverse iteration on the Jacobi-scaled matrix: an orthonormal basis (in scaled
/// coordinates) of its lowest `BLOCK` eigenvectors, returned in unscaled coordinates.
///
/// When the structure is a mechanism, round-off of the factorization mixes its null mode with
/// the lowest deforming modes whose eigenvalues are not far above round-off (those of a
/// member of many elements); a single vector of inverse iteration is such a mixture, while
/// the span of a few of them holds the null mode much more accurately.
fn block_inverse_iteration(llt: &Llt<usize, f64>, diag: &[f64], iters: usize) -> Vec<Vec<f64>> {
    let n = diag.len();
    let k = BLOCK.min(n);
    let sq: Vec<f64> = diag
        .iter()
        .map(|d| d.abs().max(f64::MIN_POSITIVE).sqrt())
        .collect();
    let start = pseudo_random(n * k);
    let mut v = Mat::<f64>::from_fn(n, k, |i, j| start[j * n + i]);
    let orthonormalize = |v: &mut Mat<f64>| {
        for _ in 0..2 {
            for j in 0..k {
                for i in 0..j {
                    let d: f64 = (0..n).map(|r| v[(r, i)] * v[(r, j)]).sum();
                    for r in 0..n {
                        let x = v[(r, i)];
                        v[(r, j)] -= d * x;
                    }
                }
                let nj = (0..n).map(|r| v[(r, j)] * v[(r, j)]).sum::<f64>().sqrt();
                if nj.is_finite() && nj > 0.0 {
                    for r in 0..n {
                        v[(r, j)] /= nj;
                    }
                }
            }
        }
    };
    orthonormalize(&mut v);
    for _ in 0..iters {
        let mut w = Mat::<f64>::from_fn(n, k, |i, j| v[(i, j)] * sq[i]);
        llt.solve_in_place_with_conj(Conj::No, w.as_mut());
        v = Mat::<f64>::from_fn(n, k, |i, j| w[(i, j)] * sq[i]);
        if v.col_iter().any(|c| c.iter().any(|x| !x.is_finite())) {
            break;
        }
        orthonormalize(&mut v);
    }
    (0..k)
        .map(|j| (0..n).map(|i| v[(i, j)] / sq[i]).collect())
        .collect()
}

/// The combination of `basis` (free-DOF vectors) that deforms the elements least: it
/// minimizes `Σ_e ‖k̃_e ũ_e‖² / Σ_e ‖k̃_e‖²·‖ũ_e‖²` (the squared, smooth form of
/// [`element_force_ratio`]) over the span, a small generalized eigenproblem whose matrices are
/// summed element by element, without the cancellation of the assembly.
fn least_deforming_combination(model: &Model, map: &DofMap, basis: &[Vec<f64>]) -> Vec<f64> {
    let k = basis.len();
    let phys: Vec<Vec<f64>> = basis.iter().map(|b| physical_mode(map, b)).collect();
    let mut g = Mat::<f64>::zeros(k, k);
    let mut w = Mat::<f64>::zeros(k, k);
    let mut add = |em: &ElemMat| {
        let n = em.dofs.len();
        let sq: Vec<f64> = (0..n).map(|a| em.k[a * n + a].max(0.0).sqrt()).collect();
        let live: Vec<usize> = (0..n).filter(|&a| sq[a] > 0.0).collect();
        let mut kn2 = 0.0;
        for &a in &live {
            for &b in &live {
                let kab = em.k[a * n + b] / (sq[a] * sq[b]);
                kn2 += kab * kab;
            }
        }
        // scaled displacements and forces of every basis vector on this element
        let u: Vec<Vec<f64>> = phys
            .iter()
            .map(|p| live.iter().map(|&a| sq[a] * p[em.dofs[a]]).collect())
            .collect();
        let f: Vec<Vec<f64>> = phys
            .iter()
            .map(|p| {
                live.iter()
                    .map(|&a| {
                        live.iter()
                            .map(|&b| em.k[a * n + b] / sq[a] * p[em.dofs[b]])
                            .sum::<f64>()
                    })
                    .collect()
            })
            .collect();
        for i in 0..k {
            for j in 0..k {
                let fij: f64 = f[i].iter().zip(&f[j]).map(|(x, y)| x * y).sum();
                let uij: f64 = u[i].iter().zip(&u[j]).map(|(x, y)| x * y).sum();
                g[(i, j)] += fij;
                w[(i, j)] += kn2 * uij;
            }
        }
    };
    for el in &model.elements {
        add(&element_stiffness(model, el));
    }
    for sp in &model.springs {
        add(&spring_matrix(sp));
    }
    // W = L Lᵀ (small Cholesky), C = L⁻¹ G L⁻ᵀ, smallest eigenvector y, c = L⁻ᵀ y
    let mut l = Mat::<f64>::zeros(k, k);
    for j in 0..k {
        let d = w[(j, j)] - (0..j).map(|m| l[(j, m)] * l[(j, m)]).sum::<f64>();
        if !(d > 0.0) {
            return basis[0].clone();
        }
        l[(j, j)] = d.sqrt();
        for i in j + 1..k {
            l[(i, j)] =
                (w[(i, j)] - (0..j).map(|m| l[(i, m)] * l[(j, m)]).sum::<f64>()) / l[(j, j)];
        }
    }
    let lower_solve = |b: &[f64]| {
        let mut x = vec![0.0; k];
        for i in 0..k {
            x[i] = (b[i] - (0..i).map(|m| l[(i, m)] * x[m]).sum::<f64>()) / l[(i, i)];
        }
        x
    };
    // columns of L⁻¹ G, then rows: C = L⁻¹ (L⁻¹ G)ᵀ
    let lg: Vec<Vec<f64>> = (0..k)
        .map(|j| lower_solve(&(0..k).map(|i| g[(i, j)]).collect::<Vec<_>>()))
        .collect();
    let c = {
        let cols: Vec<Vec<f64>> = (0..k)
            .map(|i| lower_solve(&(0..k).map(|j| lg[j][i]).collect::<Vec<_>>()))
            .collect();
        Mat::<f64>::from_fn(k, k, |i, j| 0.5 * (cols[j][i] + cols[i][j]))
    };
    let Ok(evd) = c.self_adjoint_eigen(Side::Lower) else {
        return basis[0].clone();
    };
    let y: Vec<f64> = (0..k).map(|i| evd.U()[(i, 0)]).collect();
    // c = L⁻ᵀ y
    let mut coef = vec![0.0; k];
    for i in (0..k).rev() {
        coef[i] = (y[i] - (i + 1..k).map(|m| l[(m, i)] * coef[m]).sum::<f64>()) / l[(i, i)];
    }
    let n = basis[0].len();
    (0..n)
        .map(|r| (0..k).map(|a| coef[a] * basis[a][r]).sum())
        .collect()
}

/// The unit round-off of double precision.
const UNIT_ROUND_OFF: f64 = f64::EPSILON / 2.0;

/// Tells a mechanism from an ill-conditioned stable structure by the lowest mode `mode` (free
/// DOFs) of eigenvalue `lambda`: see [`MECHANISM_RATIO`].
fn small_eigenvalue_error(
    model: &Model,
    asm: &Assembled,
    llt: &Llt<usize, f64>,
    lambda: f64,
) -> FemError {
    let map = &asm.map;
    let basis = block_inverse_iteration(llt, &asm.diag, 30);
    let mode = least_deforming_combination(model, map, &basis);
    let mode = &mode[..];
    let rho = element_force_ratio(model, &physical_mode(map, mode));
    if rho < MECHANISM_RATIO {
        FemError::Unstable {
            free: free_dofs_from_mode(map, mode),
            eigenvalue: lambda,
            hint: String::new(),
        }
    } else {
        FemError::IllConditioned {
            eigenvalue: lambda,
            estimated_error: (UNIT_ROUND_OFF / lambda).min(1.0),
            element_force_ratio: rho,
        }
    }
}

/// Factorizes the bonded stiffness; a mechanism is a typed error naming the free DOFs.
/// Returns the factor and the estimate of the smallest eigenvalue of the Jacobi-scaled
/// bonded stiffness (1 when there is no free DOF).
///
/// The stiffness is accepted when its Cholesky factorization succeeds and the smallest
/// eigenvalue `λ` of its Jacobi-scaled form (inverse iteration) is at least [`SINGULAR_EIG`]:
/// the relative error of the solves is then below about `u/λ` ≈ 1e-3 (`u` the unit
/// round-off; measured at a twentieth of that on beams: 1.9e-5 for the mid-span deflection of
/// a pinned–pinned beam of 2000 elements, where `u/λ` = 4.4e-4). Below it, or when the
/// factorization fails (then on `K + σ·diag K` with the smallest `σ` that factorizes), the
/// structure is either a mechanism or stable but too ill-conditioned for double precision,
/// and the eigenvalue cannot tell which: the lowest mode of a pinned–pinned beam of `N`
/// elements has `λ ≈ (π/N)⁴/12`, at round-off level from about 10⁴ elements on, and the
/// solves lose every digit there (the mid-span deflection is off by 3e-3 at N = 5000 and by
/// more than 100 % at 2·10⁴). The low modes do tell: the least deforming combination of six
/// vectors of block inverse iteration ([`least_deforming_combination`]) has an
/// [`element_force_ratio`] at round-off level for a mechanism ([`FemError::Unstable`],
/// naming the DOFs that move) and not for the smooth modes of a fine mesh
/// ([`FemError::IllConditioned`]); see [`MECHANISM_RATIO`].
pub(crate) fn factorize(
    model: &Model,
    asm: &Assembled,
) -> Result<(Option<Llt<usize, f64>>, f64), FemError> {
    let Some(kii) = asm.kii.as_ref() else {
        return Ok((None, 1.0));
    };
    // DOFs without any stiffness
    let zero: Vec<FreeDof> = asm
        .diag
        .iter()
        .enumerate()
        .filter(|(_, d)| **d <= 0.0)
        .map(|(i, _)| {
            let (node, dof) = asm.map.free_label[i];
            FreeDof {
                node,
                dof,
                amplitude: 1.0,
            }
        })
        .collect();
    if !zero.is_empty() {
        return Err(FemError::Unstable {
            free: zero,
            eigenvalue: 0.0,
            hint: " (no element, spring, support or contact link acts on them)".into(),
        });
    }
    let symbolic = SymbolicLlt::try_new(kii.symbolic(), Side::Lower)
        .map_err(|e| FemError::LinearAlgebra(format!("{e:?}")))?;
    match Llt::try_new_with_symbolic(symbolic.clone(), kii.as_ref(), Side::Lower) {
        Ok(llt) => {
            let (lambda, _) = inverse_iteration(&llt, &asm.diag, 3, 3);
            if lambda >= SINGULAR_EIG {
                return Ok((Some(llt), lambda));
            }
            let (lambda, _) = inverse_iteration(&llt, &asm.diag, 10, 200);
            Err(small_eigenvalue_error(model, asm, &llt, lambda))
        }
        Err(_) => {
            // Shifted matrix, same pattern: K + σ·diag(K), with the smallest shift that
            // factorizes, so that inverse iteration still separates the null mode of a
            // mechanism from the lowest deforming modes (eigenvalues σ and σ + λ_k).
            let n = asm.diag.len();
            let mut last = None;
            for sigma in [1e-15, 1e-14, 1e-13, 1e-12, 1e-11, 1e-10, 1e-9, 1e-8] {
                let mut trip = asm.kii_triplets.clone();
                for (i, d) in asm.diag.iter().enumerate() {
                    trip.push(Triplet::new(i, i, sigma * d));
                }
                let shifted = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &trip)
                    .map_err(|e| FemError::LinearAlgebra(format!("{e:?}")))?;
                match Llt::try_new_with_symbolic(symbolic.clone(), shifted.as_ref(), Side::Lower) {
                    Ok(llt) => {
                        let (lambda, _) = inverse_iteration(&llt, &asm.diag, 4, 200);
                        return Err(small_eigenvalue_error(
                            model,
                            asm,
                            &llt,
                            (lambda - sigma).max(0.0),
                        ));
                    }
                    Err(e) => last = Some(e),
                }
            }
            Err(FemError::LinearAlgebra(format!(
                "the bonded stiffness is not positive semidefinite ({last:?})"
            )))
        }
    }
}
