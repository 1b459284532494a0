//! Reading problem files for `unilateral`, with error messages that name the file, the line and
//! column, and the key.
//!
//! * [`read_contact_zone`]: a contact-zone problem (`.toml` or `.json`): the contact stiffness
//!   matrices, friction, gaps and loads of `formulation.md` §2, and the `[solve]` settings.
//!   Matrices may be written inline or as Matrix Market files ([`read_matrix_market`]).
//! * [`read_lcp`]: a plain LCP `w = Mz + q` (Siconos `.dat`, `.toml` or `.json`).
//! * [`read_fc2d`]: a 2D frictional contact problem in Siconos `.dat` "local" form.
//! * [`read_gmsh`]: a Gmsh mesh (MSH 4.1 or 2.2 ASCII) as the file writes it.
//!
//! Every reader returns an [`InputError`] for bad input and never panics, whatever the bytes
//! of the file. Its `Display` reads like a compiler message:
//!
//! ```text
//! problem.toml:12:7: contact_zone.Rnn: row 2 has 2 entries, expected 3 (as row 1)
//! ```
//!
//! Indices in key paths and messages are 1-based, as in the paper.
//!
//! Readers only: the answers are turned into files by `unilateral-output`, which this crate
//! does not depend on.

#![warn(missing_docs)]

mod dat;
mod error;
mod history;
mod json;
mod model;
mod msh;
mod mtx;
mod reader;
mod scan;
mod text;
mod toml_tree;
mod tree;
mod zone;

pub use dat::{read_fc2d, read_siconos_lcp, Fc2dProblem};
pub use error::{InputError, InputErrorKind, Location};
pub use model::{is_structural_model, read_model, read_problem, Problem, StructuralProblem};
pub use msh::{
    read_gmsh, GmshMesh, MshElement, MshElementType, MshNode, MshVersion, PhysicalGroup,
};
pub use mtx::read_matrix_market;
pub use zone::{read_contact_zone, read_lcp, ContactZoneProblem};
