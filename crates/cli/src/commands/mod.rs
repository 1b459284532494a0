//! One module per command: each reads its input, calls the libraries, and writes what was asked.

pub(crate) mod example;
pub(crate) mod history;
pub(crate) mod lcp;
pub(crate) mod solve;
pub(crate) mod tableau;
pub(crate) mod zone;
