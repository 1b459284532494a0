//! Soil block of 200 × 100 plane-strain QM6 elements (≈ 40 000 DOFs) resting on rigid ground
//! through 200 node-to-ground contact pairs along its base: assembly, factorization and
//! condensation times, and the peak memory (VmHWM).
//!
//! `cargo bench -p unilateral-fem --bench condense`

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use unilateral_fem::mesh::BlockGrid;
use unilateral_fem::{
    ContactPairSpec, ElementId, Load, LoadGroup, Model, NodeId, PlaneAnalysis, PlaneFormulation,
    PlaneMaterial, SupportDof,
};

/// `nx × ny` block of width `nx·h` and height `ny·h`; pairs at the base nodes 1..=pairs,
/// base node 0 pinned, right side on vertical rollers; self-weight constant, a surface load
/// variable.
pub fn soil_block(nx: usize, ny: usize, pairs: usize) -> Model {
    let h = 0.25;
    let mut m = Model::new();
    let grid = BlockGrid::new([0.0; 2], nx as f64 * h, ny as f64 * h, nx, ny);
    let id: Vec<NodeId> = grid
        .points()
        .iter()
        .map(|p| m.add_node(p[0], p[1]))
        .collect();
    let mat = PlaneMaterial::new(4.5e7, 0.27);
    let node = |i: usize, j: usize| id[grid.index(i, j)];
    for (e, cell) in grid.cells().into_iter().enumerate() {
        m.add_plane(
            cell.map(|k| id[k]),
            mat,
            PlaneAnalysis::PlaneStrain,
            PlaneFormulation::QM6,
        );
        m.add_load(
            LoadGroup::Constant,
            Load::BodyForce {
                element: ElementId(e),
                force: [0.0, -18e3],
            },
        );
    }
    m.pin(node(0, 0));
    for j in 1..=ny {
        m.add_support(node(nx, j), SupportDof::Ux);
    }
    for i in 1..=pairs.min(nx) {
        m.add_contact_pair(ContactPairSpec::to_ground(node(i, 0), [0.0, 1.0]).friction(0.4));
    }
    for i in 0..=nx / 4 {
        m.add_load(
            LoadGroup::Variable,
            Load::Nodal {
                node: node(i, ny),
                fx: 0.0,
                fy: -1e4,
                m: 0.0,
            },
        );
    }
    m
}

fn vm_hwm_kib() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn bench(c: &mut Criterion) {
    let model = soil_block(200, 100, 200);
    let before = vm_hwm_kib();
    let cz = model.condense().expect("stable");
    let s = &cz.stats;
    println!(
        "soil block 200x100 QM6, m = {}: free DOFs {}, nnz(lower K) {}, assembly {:.3} s, \
         factorization {:.3} s, condensation {:.3} s, asymmetry {:.1e}, VmHWM before {:?} KiB, after {:?} KiB",
        s.pairs, s.free_dofs, s.nnz_lower, s.assembly_s, s.factorization_s, s.condensation_s,
        s.asymmetry, before, vm_hwm_kib()
    );
    drop(cz);
    // scaling check for a future m = 2000 model of the same size (2000 × 10 elements)
    let big = soil_block(2000, 10, 2000);
    let cz = big.condense().expect("stable");
    let s = &cz.stats;
    println!(
        "soil block 2000x10 QM6, m = {}: free DOFs {}, nnz(lower K) {}, assembly {:.3} s, \
         factorization {:.3} s, condensation {:.3} s, VmHWM (process so far) {:?} KiB",
        s.pairs,
        s.free_dofs,
        s.nnz_lower,
        s.assembly_s,
        s.factorization_s,
        s.condensation_s,
        vm_hwm_kib()
    );
    drop(cz);
    let mut g = c.benchmark_group("fem");
    g.sample_size(10);
    g.bench_function("build_model_200x100", |b| {
        b.iter(|| black_box(soil_block(200, 100, 200)))
    });
    g.bench_function("condense_200x100_m200", |b| {
        b.iter(|| black_box(model.condense().unwrap()))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
