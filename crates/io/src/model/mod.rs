//! Structural model files: nodes, elements, structured meshes, supports, springs, loads and
//! contact pairs, read into a [`unilateral_fem::Model`] that holds the names the file used.
//!
//! The format is described in full in `docs/model-format.md`. In short (TOML; the same
//! structure in JSON):
//!
//! ```toml
//! [[sections]]
//! name = "beam"
//! E = 1.0
//! A = 2.0
//! I = 1.0
//!
//! [[members]]                 # a frame divided into elements, nodes beam.0 … beam.4
//! name = "beam"
//! start = [0.0, 0.0]
//! end = [4.0, 0.0]
//! divisions = 4
//! section = "beam"
//!
//! [[contact]]                 # every node of the beam on the rigid ground
//! name = "support"
//! from = "ground"
//! to = ["beam.0", "beam.2", "beam.4"]
//! normal = [0.0, 1.0]         # from `from` into `to`
//! friction = 0.6
//!
//! [[loads.variable.nodal]]
//! nodes = "beam.3"
//! fy = -1.0
//!
//! [solve]
//! tightening = 1.0
//! trace = "end"
//! ```
//!
//! [`read_problem`] reads either kind of problem file (a `[contact_zone]` table makes it a
//! contact-zone problem, anything else a structural model); [`read_model`] reads a structural
//! model only.

mod build;
mod values;

use std::path::Path;

use unilateral_contact::SolveSettings;
use unilateral_fem::Model;

use crate::error::{InputError, InputErrorKind};
use crate::reader::{format_of, Doc, Format};
use crate::tree::Value;
use crate::zone::{read_contact_zone, ContactZoneProblem};

/// A structural model read from a file, ready for analysis.
#[derive(Debug, Clone)]
pub struct StructuralProblem {
    /// The finite-element model (nodes, elements, supports, springs, loads, contact pairs),
    /// with the names the file used for nodes, elements, pairs and sets
    /// ([`Model::names`]).
    pub model: Model,
    /// The `[solve]` settings (defaults where the file gives none).
    pub settings: SolveSettings,
    /// The optional `title` of the file.
    pub title: Option<String>,
    /// The optional `units` of the file, as written (`"N, m"`).
    pub units: Option<String>,
    /// How many contact pairs each `[[contact]]` entry made, in file order, with the entry's
    /// `name` (`contact[K]`, 1-based, for an unnamed one).
    pub contact_entries: Vec<(String, usize)>,
    /// The stages of the file's `[[history]]`, their factors indexed like the model's load
    /// cases ([`Model::cases`]); `None` without a history (the paper's single load path).
    pub history: Option<Vec<unilateral_contact::Stage>>,
}

/// A problem file of either kind.
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)]
pub enum Problem {
    /// The contact zone given directly (`[contact_zone]`).
    ContactZone(ContactZoneProblem),
    /// A structural model.
    Structural(StructuralProblem),
}

/// Keys that only a structural model has.
const STRUCTURAL_KEYS: &[&str] = &["nodes", "elements", "blocks", "members"];

/// Whether a `.toml`/`.json` file is a structural model (rather than a contact-zone problem).
///
/// Decided by the top-level keys: a `contact_zone` table makes a contact-zone problem. Files
/// that cannot be read or parsed are reported as not structural (the reader then gives the
/// error).
pub fn is_structural_model(path: &Path) -> bool {
    match Doc::load(path, "a problem file") {
        Ok((_, root)) => match &root.value {
            Value::Table(entries) => {
                !entries.iter().any(|e| e.key == "contact_zone")
                    && entries
                        .iter()
                        .any(|e| STRUCTURAL_KEYS.contains(&e.key.as_str()))
            }
            _ => false,
        },
        Err(_) => false,
    }
}

/// Reads a problem file of either kind (`.toml` or `.json`): a top-level `contact_zone` table
/// makes it a contact-zone problem ([`read_contact_zone`]), anything else is read as a
/// structural model ([`read_model`]).
///
/// # Example
///
/// ```
/// use unilateral_io::{read_problem, Problem};
///
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("cantilever.toml");
/// std::fs::write(&path, r#"
/// [[sections]]
/// name = "s"
/// E = 210e9
/// A = 1e-3
/// I = 1e-6
///
/// [[members]]
/// name = "beam"
/// start = [0, 0]
/// end = [2, 0]
/// divisions = 4
/// section = "s"
///
/// [[supports]]
/// nodes = "beam.start"
/// fixed = true
///
/// [[contact]]
/// name = "tip"
/// from = "ground"
/// to = "beam.end"
/// normal = [0, 1]
/// friction = 0.3
///
/// [[loads.variable.nodal]]
/// nodes = "beam.end"
/// fy = -1000.0
/// "#)?;
/// let Problem::Structural(p) = read_problem(&path)? else { panic!() };
/// assert_eq!(p.model.nodes().len(), 5);
/// let names = p.model.names();
/// assert_eq!(names.pairs, vec!["tip".to_string()]);
/// assert_eq!(names.node(names.node_id("beam.end").unwrap()), "beam.4");
///
/// // Errors name the file, the line and the key.
/// std::fs::write(&path, "[[nodes]]\nid = 1\nx = 0\ny = \"zero\"\n")?;
/// let err = read_problem(&path).unwrap_err();
/// assert!(err.to_string().ends_with(
///     "cantilever.toml:4:5: nodes[1].y: expected a number, found a string (\"zero\")"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_problem(path: &Path) -> Result<Problem, InputError> {
    if format_of(path) == Some(Format::Dat) {
        return Err(InputError::at(
            path,
            None,
            InputErrorKind::Unsupported,
            "a .dat file is a plain LCP (read it with `unilateral lcp`); a problem file must be a .toml or .json file",
        ));
    }
    let (doc, root) = Doc::load(path, "a problem file")?;
    let top = doc.table(&root, "")?;
    if top.get("contact_zone").is_some() {
        return read_contact_zone(path).map(Problem::ContactZone);
    }
    if !top
        .entries
        .iter()
        .any(|e| STRUCTURAL_KEYS.contains(&e.key.as_str()))
    {
        // Keep the contact-zone reader's messages for files that look like one.
        if top.get("load").is_some() {
            return read_contact_zone(path).map(Problem::ContactZone);
        }
        if top.entries.is_empty() {
            return Err(InputError::at(
                path,
                None,
                InputErrorKind::MissingKey,
                "the file is empty: missing the `contact_zone` table of a contact-zone problem, \
                 or the nodes, blocks or members of a structural model",
            ));
        }
    }
    build::read(&doc, &top).map(Problem::Structural)
}

/// Reads a structural model from a `.toml` or `.json` file (see `docs/model-format.md`).
///
/// Every problem is an [`InputError`] naming the file, the line and column, and the key path
/// (e.g. `elements[3].nodes[2]`); nothing panics.
pub fn read_model(path: &Path) -> Result<StructuralProblem, InputError> {
    let (doc, root) = Doc::load(path, "a structural model")?;
    let top = doc.table(&root, "")?;
    if top.get("contact_zone").is_some() {
        return Err(doc.err(
            top.get("contact_zone").and_then(|n| n.pos),
            "contact_zone",
            InputErrorKind::Invalid,
            "this is a contact-zone problem, not a structural model (read it with read_problem or read_contact_zone)",
        ));
    }
    build::read(&doc, &top)
}
