//! Mesh generation as pure geometry: the nodes and quadrilaterals of a structured block
//! ([`BlockGrid`]), the nodes along a divided member ([`divide_segment`]), and the search and
//! merging of coincident nodes ([`PointIndex`], [`NodeMerge`]).
//!
//! These know nothing of files: a reader turns its input into their arguments and their
//! results into [`Model`](crate::Model) nodes, elements and names.

mod block;
mod coincident;
mod member;

pub use block::BlockGrid;
pub use coincident::{coincidence_tolerance, extent, NodeMerge, PointIndex};
pub use member::divide_segment;
