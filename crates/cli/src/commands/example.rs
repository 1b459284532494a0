//! The bundled examples, compiled into the binary.

use std::path::Path;

use crate::failure::Failure;

/// `(name, file name, description, content)`.
const EXAMPLES: &[(&str, &str, &str, &str)] = &[
    (
        "example1-beam",
        "example1-beam.toml",
        "the paper's Example 1 as a structure: continuous beam on three frictional supports",
        include_str!("../../../../examples/example1-beam.toml"),
    ),
    (
        "example1-contact-zone",
        "example1-contact-zone.toml",
        "the paper's Example 1 as contact-zone matrices (its Tables 1-3)",
        include_str!("../../../../examples/example1-contact-zone.toml"),
    ),
    (
        "example2-cantilever",
        "example2-cantilever.toml",
        "the paper's Example 2: 260 m cantilever on a rigid base pulled at its end (analytical answer)",
        include_str!("../../../../examples/example2-cantilever.toml"),
    ),
    (
        "example3-sheet-pile",
        "example3-sheet-pile.toml",
        "the paper's Example 3 (reconstruction): sheet pile wall in soil pushed at the top",
        include_str!("../../../../examples/example3-sheet-pile.toml"),
    ),
    (
        "sheet-pile-wall",
        "sheet-pile-wall.toml",
        "the sheet pile wall with real loads: the soil's weight, then a growing push (no tightening)",
        include_str!("../../../../examples/sheet-pile-wall.toml"),
    ),
    (
        "sheet-pile-stages",
        "sheet-pile-stages.toml",
        "the sheet pile wall loaded in stages: soil weight, push, release, push again ([[history]])",
        include_str!("../../../../examples/sheet-pile-stages.toml"),
    ),
    (
        "deck-bearings-temperature",
        "deck-bearings-temperature.toml",
        "a deck on sliding bearings under a daily temperature cycle ([[history]]: shakedown)",
        include_str!("../../../../examples/deck-bearings-temperature.toml"),
    ),
    (
        "cylinder-on-foundation",
        "cylinder-on-foundation.toml",
        "a steel cylinder pressed on a block (Hertz; Gmsh meshes, written beside it in meshes/)",
        include_str!("../../../../examples/cylinder-on-foundation.toml"),
    ),
    (
        "footing-on-soil",
        "footing-on-soil.toml",
        "a footing on soil, non-matching Gmsh meshes (written beside it in meshes/)",
        include_str!("../../../../examples/footing-on-soil.toml"),
    ),
];

/// The mesh files an example reads, `(example name, path relative to it, content)`.
const MESHES: &[(&str, &str, &str)] = &[
    (
        "cylinder-on-foundation",
        "meshes/disc-coarse.msh",
        include_str!("../../../../examples/meshes/disc-coarse.msh"),
    ),
    (
        "cylinder-on-foundation",
        "meshes/block-coarse.msh",
        include_str!("../../../../examples/meshes/block-coarse.msh"),
    ),
    (
        "footing-on-soil",
        "meshes/footing.msh",
        include_str!("../../../../examples/meshes/footing.msh"),
    ),
    (
        "footing-on-soil",
        "meshes/soil.msh",
        include_str!("../../../../examples/meshes/soil.msh"),
    ),
    // the Gmsh script both examples name as the meshes' source
    (
        "cylinder-on-foundation",
        "meshes/make.py",
        include_str!("../../../../examples/meshes/make.py"),
    ),
    (
        "footing-on-soil",
        "meshes/make.py",
        include_str!("../../../../examples/meshes/make.py"),
    ),
];

pub(crate) fn run(name: Option<&str>, to: &Path, force: bool) -> Result<(), Failure> {
    let Some(name) = name else {
        crate::output::outln!("bundled examples (write one out with `unilateral example NAME`):");
        for (n, _, d, _) in EXAMPLES {
            crate::output::outln!("  {n:<28} {d}");
        }
        return Ok(());
    };
    let Some((example, file, _, content)) = EXAMPLES
        .iter()
        .find(|(n, f, _, _)| *n == name || *f == name)
    else {
        let names: Vec<&str> = EXAMPLES.iter().map(|e| e.0).collect();
        return Err(Failure::Input(format!(
            "no example named '{name}'; the examples are: {}",
            names.join(", ")
        )));
    };
    // the model file and the meshes it reads, every one checked before any is written
    let files: Vec<(std::path::PathBuf, &str)> = std::iter::once((to.join(file), *content))
        .chain(
            MESHES
                .iter()
                .filter(|(e, _, _)| e == example)
                .map(|(_, rel, text)| (to.join(rel), *text)),
        )
        .collect();
    // a file there already is refused, but for one with these very bytes (the mesh script
    // both mesh examples share): it is left as it is
    let same =
        |p: &std::path::Path, text: &str| std::fs::read(p).is_ok_and(|b| b == text.as_bytes());
    if !force {
        if let Some((path, _)) = files
            .iter()
            .find(|(p, text)| p.exists() && !(p != &files[0].0 && same(p, text)))
        {
            return Err(Failure::Input(format!(
                "{} exists; use --force to overwrite it",
                path.display()
            )));
        }
    }
    for (path, text) in &files {
        path.parent()
            .map_or(Ok(()), std::fs::create_dir_all)
            .and_then(|_| std::fs::write(path, text))
            .map_err(|e| Failure::Input(format!("cannot write {}: {e}", path.display())))?;
        crate::output::outln!("wrote {}", path.display());
    }
    Ok(())
}
