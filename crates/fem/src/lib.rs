//! Linear elastic 2D structural finite elements and condensation to the contact zone.
//!
//! Build a [`Model`] (nodes, frames, bars, plane elements, springs, supports, loads in named
//! load cases, contact pairs), call [`Model::condense`] to obtain the contact stiffness
//! matrix `R = [[Rnn, Rnt], [Rtn, Rtt]]` and the contact load vectors of `formulation.md` §2
//! ([`Condensed`]), solve the contact problem elsewhere, and call [`Condensed::recover`] with
//! the [`LinkValues`] of a solution to get displacements, reactions, internal forces and
//! stresses ([`Results`]).
//!
//! Load cases: every load belongs to a case ([`Model::add_case`] → [`CaseId`],
//! [`Model::add_case_load`]); the paper's two groups ([`LoadGroup::Constant`],
//! [`LoadGroup::Variable`], [`Model::add_load`]) are the cases named `constant` and
//! `variable`. [`Condensed::cases`] holds the link forces of every case at factor 1 and
//! [`Condensed::constant`] / [`Condensed::variable`] those of the two groups (zero when the
//! model has no such case); [`Condensed::recover`] is the paper's load `constant + p·variable`,
//! [`Condensed::recover_at`] any combination of the cases (a stage of a load history).
//!
//! A model may carry the names of its items ([`Names`], [`Model::names`]); structured meshes
//! (block grids, divided members, coincident nodes) are pure geometry in [`mesh`].
//!
//! Layout: `model.rs` (the builder and its checks), `elements/` (one file per element kind
//! behind one interface; a new kind is a file there and a line in `elements::unit`), the
//! condensation in steps (`dofs.rs` numbering, `assemble.rs`, `stability.rs` factorization
//! and mechanism diagnosis, `schur.rs`, `condense.rs` the entry point), `recover.rs`, and
//! `results.rs` with the public result types.
//!
//! Sign conventions (see `docs/fem.md`): for a pair (A, B) with unit normal `n` from A into B,
//! the tangent is `t = (n_y, −n_x)`; the opening is `z_n = η + n·(u_B − u_A)` with `η` the
//! pair's initial gap (positive open, 0 closed), `z_t = t·(u_B − u_A)`; `x_n` is compression
//! positive and acts on B along `+n`, `x_t` acts on B along `+t` (and on A along `−n`, `−t`).
//! Equilibrium: `K u = f + Cᵀ x`.
//!
//! ```
//! use unilateral_fem::{ContactPairSpec, FrameSection, Load, LoadGroup, Model};
//! let mut model = Model::new();
//! let a = model.add_node(0.0, 0.0);
//! let b = model.add_node(2.0, 0.0);
//! model.add_frame(a, b, FrameSection::new(1.0, 1.0, 1.0));
//! model.fix(a);
//! model.add_contact_pair(ContactPairSpec::to_ground(b, [0.0, 1.0]).friction(0.3));
//! model.add_load(LoadGroup::Variable, Load::Nodal { node: b, fx: 0.0, fy: -1.0, m: 0.0 });
//! let c = model.condense().unwrap();
//! // a cantilever tip pushed by 1 (opening) pulls with 3EI/L³ = 0.375 on its link
//! assert!((c.rnn[(0, 0)] - 0.375).abs() < 1e-12);
//! ```

#![warn(missing_docs)]
// Index loops mirror the formulas of small dense element matrices; negated comparisons are
// deliberate so that NaN fails the positivity checks.
#![allow(
    clippy::needless_range_loop,
    clippy::too_many_arguments,
    clippy::neg_cmp_op_on_partial_ord
)]

mod assemble;
mod blocks;
mod condense;
mod dofs;
mod elements;
mod error;
pub mod mesh;
mod model;
mod names;
mod recover;
mod results;
mod schur;
mod stability;
mod stress;

pub use blocks::BondedBlocks;
pub use condense::{
    check_memory, dense_condensation_bytes, machine_memory, CondensationStats, Condensed,
};
pub use error::{DofLabel, FemError, FreeDof, Subject};
pub use model::{
    CaseId, ContactPairSpec, Element, ElementId, Endpoint, FrameSection, Load, LoadFrame,
    LoadGroup, Model, NodeId, PlaneAnalysis, PlaneFormulation, PlaneMaterial, Releases, Spring,
    SpringKind, SupportDof,
};
pub use names::Names;
pub use recover::EQUILIBRIUM_ACCEPT;
pub use results::{
    ContactLoadVector, DiagramPoint, Equilibrium, LineResult, LinkValues, PlaneResult, Reaction,
    Results, DIAGRAM_SAMPLES,
};
pub use stress::{principal, von_mises};
