//! Options of a contact solve (`[solve]` in problem files).

use crate::ContactError;

/// How far the load path is followed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Trace {
    /// Stop at the target load `p*` (Criterion 1).
    #[default]
    Target,
    /// Follow the path until the scheme stops changing (ray) or a mechanism forms, and still
    /// report the solution at `p*` when it lies on the path.
    End,
}

/// Settings of a contact solve. Defaults: `tightening = 0`, `target = 1`, `trace = Target`.
#[derive(Debug, Clone, PartialEq)]
pub struct SolveSettings {
    /// The artificial tightening `c ≥ 0` of `formulation.md` §3.
    pub tightening: f64,
    /// The target load parameter `p* > 0`.
    pub target: f64,
    /// How far the path is followed.
    pub trace: Trace,
    /// Expert option: relative pivot tolerance; `None` lets the engine scale it to the data.
    pub pivot_tolerance: Option<f64>,
    /// Expert option: maximum number of pivots; `None` means `20·(3m) + 100`.
    pub max_pivots: Option<usize>,
}

impl Default for SolveSettings {
    fn default() -> Self {
        Self {
            tightening: 0.0,
            target: 1.0,
            trace: Trace::Target,
            pivot_tolerance: None,
            max_pivots: None,
        }
    }
}

impl SolveSettings {
    /// Checks that every setting is in range.
    pub fn validate(&self) -> Result<(), ContactError> {
        if !(self.tightening.is_finite() && self.tightening >= 0.0) {
            return Err(ContactError::Settings(format!(
                "tightening must be a finite number ≥ 0, got {}",
                self.tightening
            )));
        }
        if !(self.target.is_finite() && self.target > 0.0) {
            return Err(ContactError::Settings(format!(
                "target must be a finite number > 0, got {}",
                self.target
            )));
        }
        if let Some(t) = self.pivot_tolerance {
            if !(t.is_finite() && t > 0.0 && t < 1e-2) {
                return Err(ContactError::Settings(format!(
                    "pivot_tolerance must lie in (0, 0.01), got {t}"
                )));
            }
        }
        if self.max_pivots == Some(0) {
            return Err(ContactError::Settings("max_pivots must be ≥ 1".into()));
        }
        Ok(())
    }
}
