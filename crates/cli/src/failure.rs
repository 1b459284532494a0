//! Why a run did not end with an answer, and the one mapping of every library error and every
//! ending into the contract's exit statuses.

use std::path::Path;
#[cfg(test)]
use std::path::PathBuf;

/// Why a run did not end with an answer. [`Failure::exit_code`] is the only place where a
/// failure becomes an exit status, and the `*_failure` functions below the only places where a
/// library error becomes a failure: each matches its error's variants exhaustively, so a new
/// variant does not compile until it is classified.
#[derive(Debug)]
pub(crate) enum Failure {
    /// Bad input (exit 2): the message names the file, the place in it and what is wrong.
    Input(String),
    /// The program's fault (exit 1): the message says what failed.
    Internal(String),
}

impl Failure {
    /// The outcome of steps that all ran (the writers, side by side): `Ok` if every one did,
    /// else the most serious failure (the program's before the input's, then the first), with
    /// every other failure printed on stderr first, so that none goes unsaid.
    pub(crate) fn all_of(
        results: impl IntoIterator<Item = Result<(), Failure>>,
    ) -> Result<(), Failure> {
        let mut failures: Vec<Failure> = results.into_iter().filter_map(Result::err).collect();
        if failures.is_empty() {
            return Ok(());
        }
        let worst = failures
            .iter()
            .position(|f| matches!(f, Failure::Internal(_)))
            .unwrap_or(0);
        let returned = failures.remove(worst);
        for other in &failures {
            crate::output::note(&other.message());
        }
        Err(returned)
    }

    /// The exit status of the contract: 2 bad input, 1 internal failure (0 is an answer).
    pub(crate) fn exit_code(&self) -> u8 {
        match self {
            Failure::Input(_) => 2,
            Failure::Internal(_) => 1,
        }
    }

    /// The message printed on stderr.
    pub(crate) fn message(&self) -> String {
        match self {
            Failure::Input(msg) => format!("error: {msg}"),
            Failure::Internal(msg) => format!(
                "internal error: {msg}\n\
                 This is a fault of unilateral {}, not of the input. Please report it, with the \
                 input file and the command line, to the maintainers of unilateral.",
                env!("CARGO_PKG_VERSION")
            ),
        }
    }
}

/// Where the contact zone handed to the contact solver comes from: the user typed it (a
/// contact-zone file), or the program computed it from a structural model (then a bad matrix is
/// the program's fault: the user never wrote it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum ZoneOrigin {
    /// A contact-zone problem file.
    File,
    /// Condensed from a structural model.
    Condensed,
}

/// A reader's error: always bad input; the error names the file and the place.
pub(crate) fn input_failure(e: unilateral_io::InputError) -> Failure {
    Failure::Input(e.to_string())
}

/// An error of the contact solver for the problem in `file`.
pub(crate) fn contact_failure(
    file: &Path,
    e: &unilateral_contact::ContactError,
    origin: ZoneOrigin,
) -> Failure {
    use unilateral_contact::ContactError as E;
    let internal = match e {
        // The solve settings and the per-pair data copied from the user's file (friction, gap)
        // are the user's, whatever the origin of the zone; so is a problem without pairs.
        E::Settings(_) | E::Negative { .. } | E::Empty => false,
        // Numbers whose products leave double precision: the user's extreme values, whether
        // typed in a contact-zone file or entered as a model's properties.
        E::OutOfRange(_) => false,
        // The engine failed on data that passed every check.
        E::Engine(_) => true,
        // Matrices and load vectors: the user's in a contact-zone file, the program's when they
        // were condensed from a structural model.
        E::MatrixSize { .. }
        | E::VectorSize { .. }
        | E::NotFinite { .. }
        | E::NotSymmetric { .. }
        | E::NegativeDiagonal { .. }
        | E::NotSemidefinite { .. } => origin == ZoneOrigin::Condensed,
    };
    if internal {
        Failure::Internal(format!(
            "{}: the contact zone condensed from the model was refused by the contact solver: {e}",
            file.display()
        ))
    } else {
        Failure::Input(format!("{}: {e}", file.display()))
    }
}

/// An error of the analysis of the structural model in `file`.
pub(crate) fn analysis_failure(file: &Path, e: &unilateral_analysis::AnalysisError) -> Failure {
    use unilateral_analysis::AnalysisError as E;
    match e {
        E::Model { .. } if e.is_internal() => Failure::Internal(format!("{}: {e}", file.display())),
        E::Model { .. } | E::Unstable { .. } | E::PulledApart { .. } | E::Unresolved { .. } => {
            Failure::Input(format!("{}: {e}", file.display()))
        }
        E::Contact(c) => contact_failure(file, c, ZoneOrigin::Condensed),
        // `NotOnPath` only arises where the program itself asked for a load of the path (the
        // events of a report), so it is the program's fault here.
        // The framing ("internal error", whose fault) is the CLI's; the analysis' own words for
        // it are not repeated.
        E::Internal { what, message } => {
            Failure::Internal(format!("{}: {what}: {message}", file.display()))
        }
        E::Recovery { .. } if !e.is_internal() => {
            Failure::Input(format!("{}: {e}", file.display()))
        }
        E::Recovery { .. } | E::Equilibrium { .. } | E::NotOnPath { .. } => {
            Failure::Internal(format!("{}: {e}", file.display()))
        }
    }
}

/// An error of the LCP engine on the plain LCP in `file`: the file's data was refused.
pub(crate) fn lcp_failure(file: &Path, e: &unilateral_lcp::LcpError) -> Failure {
    use unilateral_lcp::LcpError as E;
    match e {
        E::Dimension(_) | E::NotFinite { .. } | E::Settings(_) | E::Empty => {
            Failure::Input(format!("{}: {e}", file.display()))
        }
    }
}

/// A report that could not be written: the directory named on the command line.
pub(crate) fn report_failure(e: &unilateral_output::ReportError) -> Failure {
    match e {
        unilateral_output::ReportError::Io { .. } => Failure::Input(e.to_string()),
        unilateral_output::ReportError::NonFinite { .. } => Failure::Internal(e.to_string()),
        // Forces beyond the floating-point range at a load of the path: the user's extreme
        // values, as at the reported load; anything else the solution refuses is the program's.
        unilateral_output::ReportError::Contact(unilateral_contact::ContactError::OutOfRange(
            _,
        )) => Failure::Input(e.to_string()),
        unilateral_output::ReportError::Contact(_) => Failure::Internal(e.to_string()),
    }
}

/// How a load path ended: every ending is an answer except a numerical failure, which is the
/// program's fault, and a solution that should be reported and could not be verified
/// ([`unilateral_contact::ContactSolution::unreported_is_failure`]). What was computed before
/// it is still printed and written; then the run exits 1.
pub(crate) fn outcome_failure(
    file: &Path,
    sol: &unilateral_contact::ContactSolution,
) -> Option<Failure> {
    // Where the path stopped at a state beyond double precision, the data's conditioning: the
    // user's to change (exit 2), said with the sizes and the advice.
    if let Some(why) = sol.beyond_double_precision() {
        return Some(Failure::Input(format!("{}: {why}", file.display())));
    }
    ending_failure(file, &sol.outcome, sol.steps.len()).or_else(|| {
        sol.unreported_is_failure().then(|| {
            Failure::Internal(format!(
                "{}: {} — the program could not give a verified solution there; the output \
                 holds the events of the path",
                file.display(),
                sol.unreported()
                    .unwrap_or_else(|| "no solution is reported".into())
            ))
        })
    })
}

/// [`outcome_failure`] for an outcome reached after `steps` steps.
pub(crate) fn ending_failure(
    file: &Path,
    outcome: &unilateral_contact::Outcome,
    steps: usize,
) -> Option<Failure> {
    use unilateral_contact::Outcome as O;
    match outcome {
        O::TargetReached
        | O::Ray { .. }
        | O::Mechanism { .. }
        | O::ReturnedToZero
        | O::IterationLimit
        | O::NoSolutionAtStart => None,
        O::NumericalFailure => Some(Failure::Internal(format!(
            "{}: the load path stopped at a numerically singular basis after {} steps (status \
             numerical_failure); the output holds the events before it, no solution is reported",
            file.display(),
            steps
        ))),
    }
}

/// How a plain LCP solve ended: every status is an answer except a numerical failure (exit 1).
pub(crate) fn lcp_status_failure(
    file: &Path,
    status: unilateral_lcp::LcpStatus,
) -> Option<Failure> {
    use unilateral_lcp::LcpStatus as S;
    match status {
        S::Solved | S::Ray | S::IterationLimit => None,
        S::NumericalFailure => Some(Failure::Internal(format!(
            "{}: the LCP engine could not produce a verified finite solution (status \
             numerical_failure)",
            file.display()
        ))),
    }
}

/// A non-finite result is the program's fault: exit 1.
impl From<unilateral_output::NonFiniteOutput> for Failure {
    fn from(e: unilateral_output::NonFiniteOutput) -> Self {
        Failure::Internal(e.to_string())
    }
}

/// The classification of every error variant and every ending into the exit statuses of the
/// contract (reference: the contract of `docs/contact-zone.md`, "Exit status": the user's data
/// → 2, the program's own computation → 1, an answer → 0). The binary-level tests in
/// `tests/cli.rs` show the same through real runs for bad input.
/// The names of the options given, of `(name, given)` pairs, in order: what a refusal of
/// options that do not apply names.
pub(crate) fn given_options<'a>(options: &[(&'a str, bool)]) -> Vec<&'a str> {
    options
        .iter()
        .filter_map(|&(name, set)| set.then_some(name))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use unilateral_analysis::AnalysisError;
    use unilateral_contact::{ContactError, Outcome};
    use unilateral_fem::{DofLabel, ElementId, FemError};
    use unilateral_lcp::{LcpError, LcpStatus};

    fn file() -> PathBuf {
        PathBuf::from("dir/model.toml")
    }

    /// Exit status and stderr text of a failure; every message must name the file.
    fn check(f: Failure, code: u8) -> String {
        let msg = f.message();
        assert_eq!(f.exit_code(), code, "{msg}");
        assert!(
            msg.contains("dir/model.toml"),
            "the file is not named: {msg}"
        );
        match code {
            1 => {
                assert!(msg.starts_with("internal error: "), "{msg}");
                assert!(msg.contains("fault of unilateral"), "{msg}");
                assert!(msg.contains("report it"), "{msg}");
            }
            2 => {
                assert!(msg.starts_with("error: "), "{msg}");
                assert!(!msg.contains("fault of unilateral"), "{msg}");
            }
            _ => unreachable!(),
        }
        msg
    }

    fn every_contact_error() -> Vec<ContactError> {
        vec![
            ContactError::Empty,
            ContactError::MatrixSize {
                name: "Rnn",
                rows: 2,
                cols: 3,
                pairs: 3,
            },
            ContactError::VectorSize {
                name: "gap".into(),
                len: 2,
                pairs: 3,
            },
            ContactError::NotFinite {
                name: "Rnn".into(),
                index: "[1][2]".into(),
            },
            ContactError::NotSymmetric {
                name: "Rtt",
                row: 1,
                col: 2,
                upper: 1.0,
                lower: 2.0,
            },
            ContactError::NegativeDiagonal {
                name: "Rnn",
                pair: 1,
                value: -1.0,
            },
            ContactError::Negative {
                name: "friction",
                pair: 2,
                value: -0.1,
            },
            ContactError::Settings(unilateral_lcp::SettingsError::Target(0.0)),
            ContactError::OutOfRange("friction × Rnn overflows".into()),
            ContactError::Engine(unilateral_lcp::LcpError::Dimension(
                "q0 has 2 entries".into(),
            )),
        ]
    }

    /// Whether a contact error is about data the user typed in every case (settings, friction,
    /// gaps, an empty zone), not about matrices or load vectors the program may have computed.
    fn always_the_users(e: &ContactError) -> bool {
        matches!(
            e,
            ContactError::Empty
                | ContactError::Negative { .. }
                | ContactError::Settings(_)
                | ContactError::OutOfRange(_)
        )
    }

    #[test]
    fn a_contact_zone_file_is_the_users_data() {
        for e in every_contact_error() {
            // ... except a failure of the engine itself on data that passed every check.
            let code = if matches!(e, ContactError::Engine(_)) {
                1
            } else {
                2
            };
            check(contact_failure(&file(), &e, ZoneOrigin::File), code);
        }
    }

    #[test]
    fn a_condensed_contact_zone_is_the_programs() {
        // "Rnn must be positive semidefinite" about a matrix the user never wrote is not a
        // message the user can act on: it is the program's fault.
        for e in every_contact_error() {
            let code = if always_the_users(&e) { 2 } else { 1 };
            let msg = check(contact_failure(&file(), &e, ZoneOrigin::Condensed), code);
            if code == 1 && !matches!(e, ContactError::Engine(_)) {
                assert!(msg.contains("condensed from the model"), "{msg}");
            }
            let msg = check(analysis_failure(&file(), &AnalysisError::Contact(e)), code);
            assert!(!msg.is_empty());
        }
    }

    #[test]
    fn analysis_errors() {
        let fem = FemError::NonPositiveProperty {
            element: ElementId(0),
            property: "E",
            value: -1.0,
        };
        let model = AnalysisError::Model {
            message: "element `AB`: E must be positive and finite, got -1".into(),
            source: fem.clone(),
        };
        check(analysis_failure(&file(), &model), 2);
        let unstable = AnalysisError::Unstable {
            free: vec![("beam.0".into(), DofLabel::Uy)],
        };
        let msg = check(analysis_failure(&file(), &unstable), 2);
        assert!(msg.contains("node `beam.0` uy"), "{msg}");
        // The program's own computations.
        let recovery = AnalysisError::Recovery {
            at: unilateral_analysis::Place::Load(1.0),
            source: FemError::LinearAlgebra("singular".into()),
        };
        check(analysis_failure(&file(), &recovery), 1);
        let balance = AnalysisError::Equilibrium {
            at: unilateral_analysis::Place::Load(1.0),
            relative: 0.3,
        };
        let msg = check(analysis_failure(&file(), &balance), 1);
        assert!(msg.contains("out of balance"), "{msg}");
        let off_path = AnalysisError::NotOnPath {
            p: 2.0,
            end: "p = 1".into(),
        };
        check(analysis_failure(&file(), &off_path), 1);
        let internal = AnalysisError::Internal {
            what: "the contact solver refused the condensed contact zone".into(),
            message: "Rnn is not symmetric".into(),
        };
        check(analysis_failure(&file(), &internal), 1);
        let pulled = AnalysisError::PulledApart {
            pairs: vec!["base.1".into()],
            forces: vec![-10.0],
            resultant: [0.0, 10.0],
        };
        let msg = check(analysis_failure(&file(), &pulled), 2);
        assert!(msg.contains("base.1"), "{msg}");
        // The CLI's classification agrees with the analysis' own.
        for e in [model, unstable, recovery, balance, internal, pulled] {
            let code = if e.is_internal() { 1 } else { 2 };
            check(analysis_failure(&file(), &e), code);
        }
    }

    #[test]
    fn lcp_errors_are_the_files() {
        for e in [
            LcpError::Dimension("M is 2×3".into()),
            LcpError::NotFinite {
                what: "q",
                index: "2".into(),
            },
            LcpError::Settings(unilateral_lcp::SettingsError::Covering {
                entry: 0,
                value: 0.0,
            }),
            LcpError::Empty,
        ] {
            check(lcp_failure(&file(), &e), 2);
        }
    }

    /// Steps that all ran: the program's failure is returned before the input's, else the
    /// first; nothing failed, nothing returned.
    #[test]
    fn of_failures_side_by_side_the_most_serious_is_returned() {
        assert!(Failure::all_of([Ok(()), Ok(())]).is_ok());
        let input = |s: &str| Err(Failure::Input(s.into()));
        let internal = |s: &str| Err(Failure::Internal(s.into()));
        let f = Failure::all_of([input("a"), Ok(()), internal("b"), internal("c")]).unwrap_err();
        assert!(
            matches!(f, Failure::Internal(ref m) if m == "b"),
            "{}",
            f.message()
        );
        let f = Failure::all_of([Ok(()), input("a"), input("b")]).unwrap_err();
        assert!(
            matches!(f, Failure::Input(ref m) if m == "a"),
            "{}",
            f.message()
        );
    }

    #[test]
    fn every_ending_but_a_numerical_failure_is_an_answer() {
        for o in [
            Outcome::TargetReached,
            Outcome::Ray { p_from: 1.0 },
            Outcome::Mechanism {
                p_limit: 2.0,
                mode: vec![(1.0, 0.0)],
            },
            Outcome::ReturnedToZero,
            Outcome::IterationLimit,
            Outcome::NoSolutionAtStart,
        ] {
            assert!(ending_failure(&file(), &o, 3).is_none(), "{o:?}");
        }
        let f = ending_failure(&file(), &Outcome::NumericalFailure, 3).unwrap();
        let msg = check(f, 1);
        assert!(
            msg.contains("numerical_failure") && msg.contains("3 steps"),
            "{msg}"
        );
        for s in [LcpStatus::Solved, LcpStatus::Ray, LcpStatus::IterationLimit] {
            assert!(lcp_status_failure(&file(), s).is_none(), "{s:?}");
        }
        let f = lcp_status_failure(&file(), LcpStatus::NumericalFailure).unwrap();
        let msg = check(f, 1);
        assert!(msg.contains("numerical_failure"), "{msg}");
    }

    #[test]
    fn a_report_that_cannot_be_written_is_the_users_a_non_finite_picture_the_programs() {
        let io = unilateral_output::ReportError::Io {
            path: PathBuf::from("/no/such/dir/forces.svg"),
            source: std::io::Error::from(std::io::ErrorKind::NotFound),
        };
        let f = report_failure(&io);
        let msg = f.message();
        assert_eq!(f.exit_code(), 2, "{msg}");
        assert!(msg.contains("/no/such/dir/forces.svg"), "{msg}");
        let nan = unilateral_output::ReportError::NonFinite {
            file: "forces.svg",
            token: "NaN".into(),
        };
        let f = report_failure(&nan);
        let msg = f.message();
        assert_eq!(f.exit_code(), 1, "{msg}");
        assert!(msg.contains("forces.svg") && msg.contains("fault"), "{msg}");
    }

    #[test]
    fn an_input_error_keeps_the_readers_place() {
        let dir = std::env::temp_dir().join(format!("unilateral-cli-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("model.toml");
        std::fs::write(&path, "[contact_zone]\nRnn = [[1.0, 2.0], [3.0]]\n").unwrap();
        let e = unilateral_io::read_problem(&path).unwrap_err();
        let f = input_failure(e);
        let msg = f.message();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(f.exit_code(), 2);
        assert!(msg.contains(&format!("{}:2:", path.display())), "{msg}");
    }
}
