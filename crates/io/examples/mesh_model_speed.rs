//! Writes a Gmsh MSH 4.1 mesh of `nx × ny` squares cut into two triangles each (default 1000 ×
//! 500: one million triangles) into a temporary directory, with a model file that uses it through
//! `[[meshes]]` (rigid ground under the bottom line), then reads the model and prints the times of
//! the Gmsh reader alone and of the whole `read_model` (reader + model building + checks) and
//! the peak memory of the process, for docs/fem-performance.md. The mesh is not kept.
//!
//! cargo run -p unilateral-io --release --example mesh_model_speed [nx ny]
use std::fmt::Write as _;
use std::io::Write as _;
use std::time::Instant;

fn peak_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |k| k * 1024.0 / 1e6)
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("nx ny: whole numbers"))
        .collect();
    let (nx, ny) = match args.as_slice() {
        [] => (1000, 500),
        [nx, ny] => (*nx, *ny),
        _ => panic!("usage: mesh_model_speed [nx ny]"),
    };
    let dir = tempfile::tempdir().expect("a temporary directory");
    let msh = dir.path().join("grid.msh");
    let t = Instant::now();
    let node = |i: usize, j: usize| j * (nx + 1) + i + 1;
    let nodes = (nx + 1) * (ny + 1);
    let (w, h) = (nx as f64 * 0.1, ny as f64 * 0.1);
    let mut s = String::with_capacity(nodes * 40 + nx * ny * 60);
    s.push_str("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    s.push_str("$PhysicalNames\n2\n1 2 \"bottom\"\n2 1 \"soil\"\n$EndPhysicalNames\n");
    writeln!(
        s,
        "$Entities\n0 1 1 0\n1 0 0 0 {w} 0 0 1 2 0\n1 0 0 0 {w} {h} 0 1 1 0\n$EndEntities"
    )
    .unwrap();
    writeln!(s, "$Nodes\n1 {nodes} 1 {nodes}\n2 1 0 {nodes}").unwrap();
    for k in 1..=nodes {
        writeln!(s, "{k}").unwrap();
    }
    for j in 0..=ny {
        for i in 0..=nx {
            writeln!(s, "{} {} 0", i as f64 * 0.1, j as f64 * 0.1).unwrap();
        }
    }
    s.push_str("$EndNodes\n");
    let tris = 2 * nx * ny;
    writeln!(s, "$Elements\n2 {} 1 {}\n1 1 1 {nx}", nx + tris, nx + tris).unwrap();
    let mut tag = 0;
    for i in 0..nx {
        tag += 1;
        writeln!(s, "{tag} {} {}", node(i, 0), node(i + 1, 0)).unwrap();
    }
    writeln!(s, "2 1 2 {tris}").unwrap();
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (
                node(i, j),
                node(i + 1, j),
                node(i + 1, j + 1),
                node(i, j + 1),
            );
            writeln!(s, "{} {a} {b} {c}\n{} {a} {c} {d}", tag + 1, tag + 2).unwrap();
            tag += 2;
        }
    }
    s.push_str("$EndElements\n");
    std::fs::File::create(&msh)
        .and_then(|mut f| f.write_all(s.as_bytes()))
        .expect("write the mesh");
    let bytes = s.len() as f64;
    drop(s);
    let written = t.elapsed().as_secs_f64();
    let model = dir.path().join("model.toml");
    std::fs::write(
        &model,
        r#"[[materials]]
name = "soil"
E = 3.0e7
nu = 0.3

[[meshes]]
name = "g"
file = "grid.msh"
analysis = "plane_strain"
materials = { soil = "soil" }

[[contact]]
from = "ground"
to = "g.bottom"
normal = [0.0, 1.0]
friction = 0.5

[[loads.variable.nodal]]
nodes = "g.1"
fx = 1.0
"#,
    )
    .expect("write the model");
    let before = peak_mb();
    let t = Instant::now();
    let mesh = unilateral_io::read_gmsh(&msh).expect("read the mesh");
    let reader = t.elapsed().as_secs_f64();
    drop(mesh);
    let t = Instant::now();
    let p = unilateral_io::read_model(&model).expect("read the model");
    let whole = t.elapsed().as_secs_f64();
    println!(
        "{nx} × {ny} × 2 = {} triangles, {} nodes, {} pairs; .msh {:.0} MB written in {written:.2} s",
        p.model.elements().len(),
        p.model.nodes().len(),
        p.model.pairs().len(),
        bytes / 1e6
    );
    println!(
        "read_gmsh {reader:.2} s; read_model (reader + [[meshes]] + checks) {whole:.2} s; peak memory {:.0} MB (before reading {before:.0} MB)",
        peak_mb()
    );
}
