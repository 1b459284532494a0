//! A progress handle: what a long run is doing, for a front end that wants to show it.
//!
//! The engine only bumps counters (relaxed atomics, a few nanoseconds a pivot); whoever holds a
//! clone of the handle reads them from another thread ([`Progress::snapshot`]). The handle knows
//! nothing of terminals or of how progress is drawn, and the default handle is inert: every
//! bump is one branch on `None`. Progress never takes part in what the engine computes.

use std::sync::atomic::{AtomicU64, AtomicU8, Ordering};
use std::sync::Arc;

/// What a run is doing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Phase {
    /// Nothing reported yet.
    Waiting,
    /// Reading the input.
    Reading,
    /// Condensing a structure to its contact zone.
    Condensing,
    /// Finding the working scheme at the start (`p = 0`).
    Start,
    /// Following the load path.
    Path,
    /// Removing the artificial tightening at the reported load.
    Tightening,
    /// Solving a standard LCP by Lemke's method.
    Lemke,
    /// Following a stage of a load history.
    Stage,
    /// Recovering displacements, forces and stresses.
    Recovering,
    /// Writing the outputs.
    Writing,
}

impl Phase {
    const ALL: [Phase; 10] = [
        Phase::Waiting,
        Phase::Reading,
        Phase::Condensing,
        Phase::Start,
        Phase::Path,
        Phase::Tightening,
        Phase::Lemke,
        Phase::Stage,
        Phase::Recovering,
        Phase::Writing,
    ];

    fn code(self) -> u8 {
        Self::ALL.iter().position(|&p| p == self).unwrap_or(0) as u8
    }

    fn of(code: u8) -> Phase {
        Self::ALL
            .get(usize::from(code))
            .copied()
            .unwrap_or(Phase::Waiting)
    }

    /// A few words for people.
    pub fn as_str(self) -> &'static str {
        match self {
            Phase::Waiting => "starting",
            Phase::Reading => "reading the input",
            Phase::Condensing => "condensing to the contact zone",
            Phase::Start => "finding the working scheme at the start",
            Phase::Path => "following the load path",
            Phase::Tightening => "removing the tightening",
            Phase::Lemke => "solving the LCP",
            Phase::Stage => "following the load history",
            Phase::Recovering => "recovering the results",
            Phase::Writing => "writing the outputs",
        }
    }
}

#[derive(Debug, Default)]
struct Counters {
    phase: AtomicU8,
    pivots: AtomicU64,
    /// The load parameter (or a stage's `s`) as `f64` bits; `u64::MAX` (a NaN) while unknown.
    load: AtomicU64,
    steps: AtomicU64,
    stage: AtomicU64,
}

/// A cheap, cloneable progress handle shared by the engine and a front end.
///
/// `Progress::default()` reports nothing (every method returns at once); [`Progress::new`]
/// makes a live one. Clones share the same counters. Two handles always compare equal, so a
/// handle inside [`crate::Settings`] never changes what settings are.
#[derive(Clone, Default)]
pub struct Progress(Option<Arc<Counters>>);

/// What [`Progress::snapshot`] reads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Snapshot {
    /// What the run is doing.
    pub phase: Phase,
    /// Pivots made so far (every phase: the steps and the other pivots).
    pub pivots: u64,
    /// The last load parameter reached on the path (`None` before any).
    pub load: Option<f64>,
    /// Steps of the load path (changes of the working scheme) so far.
    pub steps: u64,
    /// The stage of a load history being followed (1-based; 0 outside histories).
    pub stage: u64,
}

impl Progress {
    /// A live handle.
    pub fn new() -> Self {
        let c = Counters::default();
        c.load.store(u64::MAX, Ordering::Relaxed);
        Self(Some(Arc::new(c)))
    }

    /// Whether anyone is listening.
    pub fn is_live(&self) -> bool {
        self.0.is_some()
    }

    /// Enters a phase.
    pub fn phase(&self, phase: Phase) {
        if let Some(c) = &self.0 {
            c.phase.store(phase.code(), Ordering::Relaxed);
        }
    }

    /// Adds `k` pivots that are not steps of the path (the start, the removal of the
    /// tightening, Lemke's method).
    pub fn pivots(&self, k: usize) {
        if let Some(c) = &self.0 {
            c.pivots.fetch_add(k as u64, Ordering::Relaxed);
        }
    }

    /// One step of the load path (one pivot) reached at load `p`.
    pub fn step(&self, p: f64) {
        if let Some(c) = &self.0 {
            c.steps.fetch_add(1, Ordering::Relaxed);
            c.load.store(p.to_bits(), Ordering::Relaxed);
        }
    }

    /// The path has `steps` steps and reached load `p`: for loops that report when they end.
    /// Never counts back, so it may follow [`Progress::step`] calls for the same steps.
    pub fn steps_to(&self, steps: usize, p: f64) {
        if let Some(c) = &self.0 {
            c.steps.fetch_max(steps as u64, Ordering::Relaxed);
            c.load.store(p.to_bits(), Ordering::Relaxed);
        }
    }

    /// The path is traced again from its start by another engine (a trace that was not
    /// taken): the steps and pivots counted so far, and the load reached, are dropped, so that
    /// the counts are those of the path reported.
    pub fn restart_path(&self) {
        if let Some(c) = &self.0 {
            c.steps.store(0, Ordering::Relaxed);
            c.pivots.store(0, Ordering::Relaxed);
            c.load.store(u64::MAX, Ordering::Relaxed);
        }
    }

    /// Starts the next stage of a load history (the first is 1).
    pub fn next_stage(&self) {
        if let Some(c) = &self.0 {
            c.stage.fetch_add(1, Ordering::Relaxed);
            c.phase.store(Phase::Stage.code(), Ordering::Relaxed);
        }
    }

    /// The counters now (`None` for an inert handle).
    pub fn snapshot(&self) -> Option<Snapshot> {
        let c = self.0.as_ref()?;
        let load = f64::from_bits(c.load.load(Ordering::Relaxed));
        Some(Snapshot {
            phase: Phase::of(c.phase.load(Ordering::Relaxed)),
            pivots: c.pivots.load(Ordering::Relaxed) + c.steps.load(Ordering::Relaxed),
            load: load.is_finite().then_some(load),
            steps: c.steps.load(Ordering::Relaxed),
            stage: c.stage.load(Ordering::Relaxed),
        })
    }
}

impl std::fmt::Debug for Progress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.snapshot() {
            Some(s) => f.debug_tuple("Progress").field(&s).finish(),
            None => f.write_str("Progress(none)"),
        }
    }
}

/// Progress is no setting: two handles are always equal.
impl PartialEq for Progress {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: the counts made by hand below; an inert handle reports nothing.
    #[test]
    fn clones_share_the_counters_and_the_default_is_inert() {
        let none = Progress::default();
        none.step(1.0);
        assert!(none.snapshot().is_none() && !none.is_live());
        let p = Progress::new();
        let q = p.clone();
        assert_eq!(p.snapshot().unwrap().load, None);
        q.phase(Phase::Path);
        q.pivots(3);
        q.step(0.5);
        q.step(2.5);
        let s = p.snapshot().unwrap();
        assert_eq!(
            (s.phase, s.pivots, s.steps, s.load),
            (Phase::Path, 5, 2, Some(2.5))
        );
        p.steps_to(1, 3.0);
        assert_eq!(p.snapshot().unwrap().steps, 2, "never counts back");
        p.steps_to(4, 3.0);
        let s = p.snapshot().unwrap();
        assert_eq!((s.pivots, s.steps, s.load), (7, 4, Some(3.0)));
        p.next_stage();
        p.next_stage();
        let s = p.snapshot().unwrap();
        assert_eq!((s.phase, s.stage), (Phase::Stage, 2));
        assert_eq!(Progress::new(), Progress::default());
        for ph in Phase::ALL {
            assert_eq!(Phase::of(ph.code()), ph);
        }
    }
}
