//! Frictional unilateral contact as a parametric linear complementarity problem.
//!
//! Data flow: [`ContactZone`] (the contact stiffness matrix and load vectors of a structure)
//! → the `3m` LCP of `formulation.md` §3 → the load path of the parametric Lemke method
//! → pair states and events.

mod error;
mod settings;
mod zone;

pub use error::ContactError;
pub use settings::{SolveSettings, Trace};
pub use zone::{ContactLoad, ContactZone};
