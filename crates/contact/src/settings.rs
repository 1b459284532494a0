//! Options of a contact solve (`[solve]` in problem files).

use unilateral_lcp::{Follow, PathOptions, Settings, Tightening};

use crate::ContactError;

/// Settings of a contact solve. Defaults: `tightening = 0`, `target = 1`,
/// `follow = Follow::ToTarget`, the engine's default settings.
#[derive(Debug, Clone, PartialEq)]
pub struct SolveSettings {
    /// The artificial tightening `c ≥ 0` of `formulation.md` §3.
    pub tightening: f64,
    /// The target load parameter `p* > 0`.
    pub target: f64,
    /// How far the load path is followed: to the target load `p*` (Criterion 1), or to its end
    /// (ray or mechanism), the solution at `p*` still reported when it lies on the path.
    pub follow: Follow,
    /// Expert options of the engine (`pivot_tolerance`, `max_pivots`, `refactor_interval`);
    /// `None` lets the engine scale them to the data (at most `20·(3m) + 100` pivots). The
    /// lexicographic order and the covering direction are the formulation's own (see
    /// [`crate::ContactLcp`]) and replace those given here.
    pub engine: Settings,
}

impl Default for SolveSettings {
    fn default() -> Self {
        Self {
            tightening: 0.0,
            target: 1.0,
            follow: Follow::ToTarget,
            engine: Settings::default(),
        }
    }
}

impl SolveSettings {
    /// Checks that every setting is in range: the tightening, the target, then the engine's
    /// own settings, each by the engine's check ([`ContactError::Settings`]).
    pub fn validate(&self) -> Result<(), ContactError> {
        Tightening::check_amount(self.tightening)?;
        PathOptions::check_target(self.target)?;
        self.engine.validate_values()?;
        Ok(())
    }
}
