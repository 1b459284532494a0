//! A generated sweep of block load histories judged by hand: whatever a stage's trace meets,
//! it never answers with a mechanism, a turn of the path or a carried load away from the
//! block's tipping load (a numerical failure is allowed: it is said to be the program's).

use unilateral_contact::StageStatus;

use crate::surface::{analyze_history_text, block_history_text, read};

/// A replayable sequence of numbers in `[0, 1)`.
struct Sequence(u64);

impl Sequence {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn pick<T: Copy>(&mut self, of: &[T]) -> T {
        of[((self.next() * of.len() as f64) as usize).min(of.len() - 1)]
    }

    /// The next generated block: meshes 2–8 × 1–4, three proportions, friction 0.2–0.5,
    /// springs of 100 N/m to 1e5 N/m, weights of 8–10 kN.
    fn block(&mut self) -> Block {
        let mesh = (
            2 + (self.next() * 7.0) as usize,
            1 + (self.next() * 4.0) as usize,
        );
        let (b, h) = self.pick(&[(1.0, 0.5), (2.0, 1.0), (1.0, 1.0)]);
        let f = ((0.2 + 0.3 * self.next()) * 100.0).round() / 100.0;
        let k = self.pick(&[100.0, 178.0, 300.0, 562.0, 1000.0, 1e4, 1e5]);
        let w = (8000.0 + 2000.0 * self.next()).round();
        Block {
            mesh,
            size: (b, h),
            f,
            k,
            w,
            tip: w * b / (2.0 * h) / 10_000.0,
        }
    }
}

/// A generated steel block ([`block_history_text`]'s parameters).
struct Block {
    /// Elements along the base and up the height.
    mesh: (usize, usize),
    /// Width and height, m.
    size: (f64, f64),
    /// Friction coefficient.
    f: f64,
    /// The spring at the heel, N/m.
    k: f64,
    /// Weight, N.
    w: f64,
    /// The push's factor (of 10 kN) at which it tips by hand, `w·b/(2h)`.
    tip: f64,
}

/// 600 steel blocks (meshes 2–8 × 1–4, three proportions, friction 0.2–0.5, springs of
/// 100 N/m to 1e5 N/m, weights of 8–10 kN, half in kN·mm), each with its weight, a push to
/// 0.5–1.5 of its tipping load `P = W·B/(2H)` and, for two thirds of them, a third stage that
/// unloads it or pushes it back to half that load the other way. By hand a stage can end in
/// a mechanism only at the tipping load (about the toe, or about the heel when pushed back:
/// the spring acts at the base, with no moment about either), and carries no load beyond it.
/// Such sweeps found stages answering with a mechanism at 0.3–0.9 of the tipping load (a mode
/// in which nothing moved: `docs/history.md`, "A mechanism in which nothing moves").
#[test]
fn generated_block_histories_end_only_at_the_tipping_load() {
    let mut seq = Sequence(35);
    let (mut answered, mut tipped, mut failed) = (0, 0, 0);
    for case in 0..600 {
        let Block {
            mesh,
            size: (b, h),
            f,
            k,
            w,
            tip,
        } = seq.block();
        let push = tip * seq.pick(&[0.5, 0.93, 0.99, 1.0, 1.2, 1.5]);
        let third = seq.pick(&[None, Some(0.0), Some(-0.5 * tip)]);
        let kn_mm = case % 2 == 1;
        let pushes: Vec<f64> = std::iter::once(push).chain(third).collect();
        let what = format!(
            "case {case}: {mesh:?} mesh, {b} × {h} m, f = {f}, k = {k}, W = {w}, pushes \
             {pushes:?} (tipping at {tip}), kN·mm {kn_mm}"
        );
        let text = block_history_text((mesh.0, mesh.1, b, h), (f, k, w), &pushes, kn_mm);
        // A refusal (slips beyond what double precision resolves) is no answer either.
        let a = match analyze_history_text(&text) {
            Ok(a) => a,
            Err(_) => {
                failed += 1;
                continue;
            }
        };
        let mut from = 0.0;
        for (st, &to) in a.history.stages[1..].iter().zip(&pushes) {
            let load = from + st.s_end * (to - from);
            // Only a mechanism has a mode.
            assert!(
                st.status == StageStatus::Mechanism || st.mechanism.is_none(),
                "{what}: {:?} with a mechanism's mode",
                st.status
            );
            let at_tipping = (load.abs() - tip).abs() <= 1e-5 * tip;
            match st.status {
                StageStatus::Completed => {
                    assert!(
                        load.abs() <= tip * (1.0 + 1e-5),
                        "{what}: a stage carried {load}"
                    );
                    answered += 1;
                }
                StageStatus::Mechanism | StageStatus::Indeterminate => {
                    assert!(
                        at_tipping,
                        "{what}: {:?} at {load}: {:?}",
                        st.status, st.reason
                    );
                    tipped += 1;
                }
                StageStatus::NumericalFailure
                | StageStatus::IterationLimit
                | StageStatus::Unresolved => failed += 1,
            }
            from = to;
        }
    }
    // The sweep is not empty of answers: most stages are answered by hand (the failures are
    // the soft springs' slips of metres, `docs/history.md`).
    assert!(
        answered + tipped > 2 * failed,
        "{answered} answered, {tipped} tipped, {failed} failed"
    );
    eprintln!("{answered} stages completed, {tipped} tipped, {failed} failed or refused");
}

/// A generated steel block ([`block_history_text`]'s parameters) on the load path — its weight
/// the constant load, its push (10 kN at the top corner) the variable one —, analysed without
/// a tightening to `target`, followed as `follow` says.
fn analyze_block_path(
    mesh: (usize, usize, f64, f64),
    spring: (f64, f64, f64),
    kn_mm: bool,
    (target, follow): (f64, unilateral_contact::Follow),
    what: &str,
) -> Result<unilateral_analysis::Analysis, unilateral_analysis::AnalysisError> {
    let text = block_history_text(mesh, spring, &[], kn_mm);
    let text = text
        .split("[[history]]")
        .next()
        .unwrap_or_default()
        .replace("[[loads.weight.nodal]]", "[[loads.constant.nodal]]")
        .replace("[[loads.push.nodal]]", "[[loads.variable.nodal]]");
    let p = read("block.toml", &text).unwrap_or_else(|e| panic!("{what}: {e}"));
    let settings = unilateral_contact::SolveSettings {
        tightening: 0.0,
        target,
        follow,
        ..Default::default()
    };
    unilateral_analysis::analyze(&p.model, &settings)
}

/// The next generated block on the load path: its spring drawn from `springs` where given,
/// a target of 0.5–1.5 of its tipping load, followed to it or to the path's end, in kN·mm for
/// the odd cases. Its description, its tipping load, its target and its analysis.
fn next_block_path(
    seq: &mut Sequence,
    case: usize,
    springs: Option<&[f64]>,
) -> (
    String,
    f64,
    f64,
    Result<unilateral_analysis::Analysis, unilateral_analysis::AnalysisError>,
) {
    use unilateral_contact::Follow;
    let Block {
        mesh,
        size: (b, h),
        f,
        k,
        w,
        tip,
    } = seq.block();
    let k = springs.map_or(k, |s| seq.pick(s));
    let target = tip * seq.pick(&[0.5, 0.93, 0.99, 1.0, 1.2, 1.5]);
    let follow = seq.pick(&[Follow::ToTarget, Follow::ToEnd]);
    let kn_mm = case % 2 == 1;
    let what = format!(
        "case {case}: {mesh:?} mesh, {b} × {h} m, f = {f}, k = {k}, W = {w}, target \
         {target} (tipping at {tip}), {follow:?}, kN·mm {kn_mm}"
    );
    let a = analyze_block_path(
        (mesh.0, mesh.1, b, h),
        (f, k, w),
        kn_mm,
        (target, follow),
        &what,
    );
    (what, tip, target, a)
}

/// The same kind of blocks (300 of them, half in kN·mm) on the load path: the weight constant
/// and the push growing with `p`, to a target of 0.5–1.5 of the tipping load or to the end of
/// the path. By hand the path ends in the mechanism at the tipping load, and reaches a target
/// only below it; a ray or a return to zero is wrong for these blocks. A sweep of 3024 such
/// runs found every mechanism within 2.7e-6 of the tipping load (`docs/performance.md`, round
/// 35); a failure or a refusal (the soft springs' slips of metres) is allowed.
#[test]
fn generated_block_paths_end_only_at_the_tipping_load() {
    use unilateral_analysis::Outcome;
    let mut seq = Sequence(3035);
    let (mut answered, mut failed) = (0, 0);
    for case in 0..300 {
        let (what, tip, target, a) = next_block_path(&mut seq, case, None);
        let Ok(a) = a else {
            failed += 1;
            continue;
        };
        match a.solution.outcome {
            Outcome::Mechanism { p_limit, .. } => assert!(
                (p_limit - tip).abs() <= 1e-5 * tip,
                "{what}: a mechanism at {p_limit}"
            ),
            Outcome::TargetReached => {
                assert!(target <= tip * (1.0 + 1e-5), "{what}: the target reached")
            }
            Outcome::NumericalFailure | Outcome::IterationLimit => {
                failed += 1;
                continue;
            }
            ref other => panic!("{what}: {other:?}"),
        }
        answered += 1;
    }
    assert!(
        answered > 2 * failed,
        "{answered} answered, {failed} failed"
    );
    eprintln!("{answered} paths answered, {failed} failed or refused");
}

/// Steel blocks (1 m × 1 m) held by heel springs of 10 and 2 N/m — 5e-11 and 1e-11 of the
/// block's stiffness —, weighed and pushed at the top to half their tipping load, the path
/// traced to its end. By hand: at the target the pairs carry the weight `W` and the push (all
/// of it, or `f·W` where the push has passed the friction's capacity and the block slides
/// against the spring), and the path ends in the mechanism at the tipping load `W·B/(2H)` (the
/// spring acts at the base, with no moment about the toe). Each failed in one of N·m and
/// kN·mm (exit 1): at the tipping the direction in which the heel lifts holds the load, but
/// the condensed data gave the toe's normal force a fall of 5e-7 of the column — round-off of
/// the slips of hundreds of metres — and the pivot on it left a singular basis. Judged on the
/// structure's equations (`TINY_PIVOT`), the limit is within 1e-4 of the statics' (4.6e-5 at
/// most here: the slips' round-off; the sweep above asks 1e-5 of stiffer springs).
#[test]
fn blocks_on_soft_heel_springs_tip_at_the_load_by_hand_in_both_units() {
    use unilateral_analysis::Outcome;
    use unilateral_contact::Follow;
    for (mesh, f, k, w) in [
        ((5, 4), 0.45, 10.0, 8902.0),
        ((2, 1), 0.24, 10.0, 9885.0),
        ((8, 1), 0.44, 2.0, 8065.0),
    ] {
        let tip = w / 2.0 / 10_000.0;
        let target = tip / 2.0;
        for kn_mm in [false, true] {
            let what = format!("{mesh:?} mesh, f = {f}, k = {k}, W = {w}, kN·mm {kn_mm}");
            let mesh = (mesh.0, mesh.1, 1.0, 1.0);
            let a = analyze_block_path(mesh, (f, k, w), kn_mm, (target, Follow::ToEnd), &what)
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            match a.solution.outcome {
                Outcome::Mechanism { p_limit, .. } => assert!(
                    (p_limit - tip).abs() <= 1e-4 * tip,
                    "{what}: a mechanism at {p_limit} against {tip}"
                ),
                ref other => panic!("{what}: {other:?}"),
            }
            let force = if kn_mm { 1e-3 } else { 1.0 };
            let pairs = &a.solution.pairs;
            let n: f64 = pairs.iter().map(|r| r.x_n).sum::<f64>() / force;
            let t: f64 = pairs.iter().map(|r| r.x_t).sum::<f64>() / force;
            let push = target * 10_000.0;
            let friction = push.min(f * w);
            assert!((n - w).abs() <= 1e-6 * w, "{what}: ΣN = {n}");
            assert!((t.abs() - friction).abs() <= 1e-6 * w, "{what}: ΣT = {t}");
        }
    }
}

/// A steel block (1 m × 1 m, 4 × 3 elements, friction 0.49, W = 9692 N) held by a heel spring
/// of 5 N/m, weighed in one stage and pushed in the next to 1.2 times its tipping load
/// `W·B/(2H)`: by hand the push stage ends in the mechanism at the tipping load. In N·m it
/// stopped there at a singular basis (a numerical failure: exit 1), the condensed data's
/// toe force falling at round-off of the slips; judged on the structure's equations
/// (`Pivoter::tiny_pivot_mechanism`), the mechanism, in both units.
#[test]
fn a_block_on_a_soft_heel_spring_pushed_past_its_tipping_load_in_a_stage_tips_there() {
    let (w, tip) = (9692.0, 9692.0 / 2.0 / 10_000.0);
    let push = 1.2 * tip;
    for kn_mm in [false, true] {
        let what = format!("kN·mm {kn_mm}");
        let text = block_history_text((4, 3, 1.0, 1.0), (0.49, 5.0, w), &[push], kn_mm);
        let a = analyze_history_text(&text).unwrap_or_else(|e| panic!("{what}: {e}"));
        let st = &a.history.stages[1];
        assert_eq!(st.status, StageStatus::Mechanism, "{what}: {:?}", st.reason);
        let load = st.s_end * push;
        assert!(
            (load - tip).abs() <= 1e-4 * tip,
            "{what}: tipped at {load} against {tip}"
        );
    }
}

/// Steel blocks on heel springs of 1 and 10 N/m (N·m) traced past their tipping load, to the
/// end: by hand the path ends at the tipping load `W·B/(2H)`, where the block has slid
/// `(P − f·W)/k` — 200 m and more, whose links' forces (1e14 N term by term) leave the state
/// beyond what double precision resolves beside forces of 1e4 N. After the tipping their paths
/// met a step that would have carried the load 1e7 to 1e11 times beyond itself, on a slip
/// reversing, and stopped at a singular basis (exit 1, the program's fault). Judged on the
/// structure's equations (`FAR_STEP`): refused as unresolvable at the tipping load (exit 2,
/// the advice about the spring).
#[test]
fn blocks_on_soft_heel_springs_past_their_tipping_load_are_refused_there_not_failed() {
    use unilateral_analysis::{AnalysisError, Place};
    use unilateral_contact::Follow;
    for (mesh, (b, h), f, k, w) in [
        ((5, 2), (1.0, 1.0), 0.38, 1.0, 8112.0),
        ((7, 2), (2.0, 1.0), 0.39, 10.0, 8395.0),
    ] {
        let tip = w * b / (2.0 * h) / 10_000.0;
        let what = format!("{mesh:?} mesh, {b} × {h} m, f = {f}, k = {k}, W = {w}");
        let mesh = (mesh.0, mesh.1, b, h);
        match analyze_block_path(mesh, (f, k, w), false, (1.2 * tip, Follow::ToEnd), &what) {
            Err(
                e @ AnalysisError::Unresolved {
                    at: Place::Load(p), ..
                },
            ) => {
                assert!(!e.is_internal(), "{what}: {e}");
                assert!(
                    (p - tip).abs() <= 1e-4 * tip,
                    "{what}: refused at {p}, tipping {tip}"
                );
            }
            other => panic!("{what}: {:?}", other.map(|a| a.solution.outcome)),
        }
    }
}

/// Steel blocks (1 m × 1 m) on heel springs of 30 and 100 N/m, pushed at the top to the end of
/// the path: by hand the path ends in the mechanism at the tipping load `W·B/(2H)` (the spring
/// acts at the base, with no moment about the toe), where the block has slid `(P − f·W)/k`:
/// 10.7 m and 4.1 m. Where the heel pair opens, the direction in which it lifts holds the
/// load, but the condensed data gave the load a rate of −2.7e-15 of the column and a block
/// 1e9 away, a step that moved the load by less than the 1e-6 of itself that a judged step
/// must carry: the pivot on it (the block rotated a billion times its slip about its toe) left
/// values of round-off, from which the 30 N/m block (kN·mm) went on to a false mechanism at
/// p = 0.575 without a state (exit 1, the program's fault) and the 100 N/m block (kN·mm)
/// stopped at a singular basis (refused as beyond double precision). Judged on the
/// structure's equations as a runaway step (`Pivoter::run`): the mechanism at the tipping load
/// in both units, or (the 30 N/m block in kN·mm, whose slips' forces are 1.1e9 times its own)
/// the state there refused as beyond double precision — never a mechanism elsewhere, never
/// the program's fault. Below the tipping load the 100 N/m block's pairs carry `W` and the
/// push, which is below the friction's capacity.
#[test]
fn blocks_on_30_and_100_n_per_m_springs_tip_at_the_load_by_hand_in_both_units() {
    use unilateral_analysis::{AnalysisError, Outcome, Place};
    use unilateral_contact::Follow;
    for (mesh, f, k, w, target) in [
        ((7, 4), 0.46, 30.0, 8052.0, 0.48312),
        ((5, 2), 0.45, 100.0, 8184.0, 0.2046),
    ] {
        let tip = w / 2.0 / 10_000.0;
        for kn_mm in [false, true] {
            let what = format!("{mesh:?} mesh, f = {f}, k = {k}, W = {w}, kN·mm {kn_mm}");
            let mesh = (mesh.0, mesh.1, 1.0, 1.0);
            let a = match analyze_block_path(mesh, (f, k, w), kn_mm, (target, Follow::ToEnd), &what)
            {
                Ok(a) => a,
                Err(
                    e @ AnalysisError::Unresolved {
                        at: Place::Load(p), ..
                    },
                ) if k == 30.0 => {
                    assert!(!e.is_internal(), "{what}: {e}");
                    assert!(
                        (p - tip).abs() <= 1e-4 * tip,
                        "{what}: refused at {p}, tipping {tip}"
                    );
                    continue;
                }
                Err(e) => panic!("{what}: {e}"),
            };
            match a.solution.outcome {
                Outcome::Mechanism { p_limit, .. } => assert!(
                    (p_limit - tip).abs() <= 1e-4 * tip,
                    "{what}: a mechanism at {p_limit} against {tip}"
                ),
                ref other => panic!("{what}: {other:?}"),
            }
            if target < tip {
                let force = if kn_mm { 1e-3 } else { 1.0 };
                let pairs = &a.solution.pairs;
                let n: f64 = pairs.iter().map(|r| r.x_n).sum::<f64>() / force;
                let t: f64 = pairs.iter().map(|r| r.x_t).sum::<f64>() / force;
                let push = target * 10_000.0;
                assert!(push < f * w, "{what}: the push slides the block");
                assert!((n - w).abs() <= 1e-6 * w, "{what}: ΣN = {n}");
                assert!((t.abs() - push).abs() <= 1e-6 * w, "{what}: ΣT = {t}");
            }
        }
    }
}

/// The blocks of [`generated_block_paths_end_only_at_the_tipping_load`] on heel springs of 1 to
/// 10 N/m (200 of them, half in kN·mm): the soft spring an engineer adds to hold a free body,
/// 5e-12 to 5e-11 of the block's stiffness, which lets it slide hundreds of metres past its
/// friction's capacity. By hand the path ends in the mechanism at the tipping load, and reaches
/// a target only below it; a return to zero or a ray that reports a state is wrong. A refusal
/// (exit 2: the slips' forces beyond what double precision resolves beside the block's) is
/// allowed, a failure said to be the program's (exit 1) is not. Before the rule of
/// `docs/engine.md`, "Tiny pivots on soft springs": 60 such failures, and three wrong answers
/// (returns to zero at the tipping load); after it 8 failures (paths stopped at a singular
/// basis, or without the state they should report, at slips of kilometres), refused since as
/// states beyond double precision (`ContactSolution::beyond_double_precision`). 16 answered
/// then, 17 now, the rest refused.
#[test]
fn generated_blocks_on_soft_heel_springs_end_only_at_the_tipping_load() {
    use unilateral_analysis::Outcome;
    let mut seq = Sequence(4301);
    let (mut answered, mut refused, mut failed) = (0, 0, 0);
    for case in 0..200 {
        let (what, tip, target, a) = next_block_path(&mut seq, case, Some(&[1.0, 2.0, 5.0, 10.0]));
        let a = match a {
            Ok(a) => a,
            Err(e) if e.is_internal() => {
                failed += 1;
                continue;
            }
            Err(_) => {
                refused += 1;
                continue;
            }
        };
        // A path that stopped without an answer at a state beyond double precision is refused
        // (exit 2), as the command line says.
        if let Some(why) = a.solution.beyond_double_precision() {
            assert!(why.contains("keep the slips short"), "{what}: {why}");
            refused += 1;
            continue;
        }
        // A path past the tipping load that reports no state there (the program's fault, as
        // the command line says) is a failure, not an answer.
        let reported = a.solution.p.is_some();
        match a.solution.outcome {
            Outcome::Mechanism { p_limit, .. } => assert!(
                (p_limit - tip).abs() <= 2e-4 * tip,
                "{what}: a mechanism at {p_limit}"
            ),
            Outcome::TargetReached | Outcome::Ray { .. } if !reported => {
                failed += 1;
                continue;
            }
            Outcome::TargetReached => {
                assert!(target <= tip * (1.0 + 2e-4), "{what}: the target reached")
            }
            Outcome::NumericalFailure | Outcome::IterationLimit => {
                failed += 1;
                continue;
            }
            ref other => panic!("{what}: {other:?} at {:?}", a.solution.p),
        }
        answered += 1;
    }
    eprintln!("{answered} answered, {refused} refused, {failed} failed");
    assert!(
        failed == 0 && answered > 10,
        "{answered} answered, {refused} refused, {failed} failed"
    );
}

/// Two blocks of a generated sweep on 1 N/m heel springs whose paths stopped without an answer
/// as the program's fault (exit 1): one at a singular basis at its tipping load `W·B/(2H)`
/// (N·m: 5 × 2 mesh, 1 m × 0.5 m, f = 0.34, W = 8318 N), one past it on a ray with no state at
/// its target (kN·mm: 5 × 1 mesh, 2 m × 1 m, f = 0.45, W = 8516 N). Both have slid, by hand,
/// `(P − f·W)/k` at the tipping load `P`: 5490 m and 4685 m, slips whose forces (1e15 N and
/// 2e12 kN term by term) are beyond what double precision resolves beside loads of kilonewtons.
/// Both are refused as such (the sentence gives the slip, within 1e-3 of the hand value).
#[test]
fn blocks_stopped_at_kilometres_of_slip_on_the_path_are_beyond_double_precision() {
    use unilateral_contact::Follow;
    for (mesh, spring, kn_mm, target) in [
        ((5, 2, 1.0, 0.5), (0.34, 1.0, 8318.0), false, 0.99816),
        ((5, 1, 2.0, 1.0), (0.45, 1.0, 8516.0), true, 1.02192),
    ] {
        let what = format!("{mesh:?}, {spring:?}, kN·mm {kn_mm}");
        let (b, h) = (mesh.2, mesh.3);
        let (f, k, w) = spring;
        let tip = w * b / (2.0 * h);
        let slip = (tip - f * w) / k * if kn_mm { 1e3 } else { 1.0 };
        let a = analyze_block_path(mesh, spring, kn_mm, (target, Follow::ToEnd), &what)
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        let why = a
            .solution
            .beyond_double_precision()
            .unwrap_or_else(|| panic!("{what}: {:?}", a.solution.outcome));
        let largest: f64 = why
            .split("(largest ")
            .nth(1)
            .and_then(|r| r.split(')').next())
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("{what}: {why}"));
        assert!(
            (largest - slip).abs() <= 1e-3 * slip,
            "{what}: slip {largest} against {slip} by hand: {why}"
        );
        assert!(
            why.contains("cannot be resolved in double precision"),
            "{what}: {why}"
        );
    }
}

/// `tests/data/unresolvable/block-sliding-on-soft-foundation-kn-mm.toml`: a steel block lying
/// without friction on a soft foundation, held by a 41.4 N/m spring, has slid `P/k` = 345.6 m
/// by hand at its target. Its state there (found since round 45's start rules; "no solution at
/// the start" before), out of balance by 2.1e-6, was said to be the program's fault (exit 1):
/// the links' couplings are the foundation's (38 kN/mm), and their
/// terms 1.3e7 times the forces allowed only 1.8e-7 of round-off — but the block's own nodes
/// move with the slip, and its elements' terms are 1.7e9 times the forces. Refused as beyond
/// double precision at the target (exit 2), with the terms of the elements.
#[test]
fn a_block_sliding_hundreds_of_metres_on_a_soft_foundation_is_beyond_double_precision() {
    use unilateral_analysis::{AnalysisError, Place};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/unresolvable/block-sliding-on-soft-foundation-kn-mm.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("the test data file {} is missing: {e}", path.display()));
    let p = read("block.toml", &text).unwrap_or_else(|e| panic!("{e}"));
    match unilateral_analysis::analyze(&p.model, &p.settings) {
        Err(
            e @ AnalysisError::Unresolved {
                at: Place::Load(load),
                dislocation,
                forces,
                ..
            },
        ) => {
            assert!(!e.is_internal(), "{e}");
            assert_eq!(load, 0.5, "{e}");
            // The block's elements: its stiffness times 345.6 m, beside forces of 14.3 kN.
            assert!(dislocation / forces > 1e9, "{e}");
        }
        other => panic!("{:?}", other.map(|a| a.solution.outcome)),
    }
}

/// `tests/data/unresolvable/block-soft-spring-ending-{n-m,kn-mm}.toml`: a steel block held by an
/// 11.4 N/m spring at its top, whose path ends where, by statics, it becomes a mechanism
/// (p = 9.4926), having slid kilometres. Read from that state, the ending was a ray in N·m and a
/// return to zero in kN·mm: both now carry the doubt (the reading says the state there cannot
/// be resolved in double precision), without refusing the run. The state at the target 0.5 is
/// an ordinary one, by statics: the pairs carry the block's weight (its body force times its
/// volume and the two nodal loads on its top) and the whole push (the spring's share, 11.4 N/m
/// times micrometres, is below 1e-7 of it).
#[test]
fn a_path_ending_at_kilometres_of_slip_says_its_ending_is_in_doubt_in_both_units() {
    use unilateral_analysis::Outcome;
    let weight = 16287.915361971216 * 1.9 * 1.427 * 0.633 + 2.0 * 40910.16347024467;
    let push = 0.5 * 11746.16048899237;
    for (file, force) in [
        ("block-soft-spring-ending-n-m.toml", 1.0),
        ("block-soft-spring-ending-kn-mm.toml", 1e-3),
    ] {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/data/unresolvable")
            .join(file);
        let text = std::fs::read_to_string(&path)
            .unwrap_or_else(|e| panic!("the test data file {} is missing: {e}", path.display()));
        let p = read("block.toml", &text).unwrap_or_else(|e| panic!("{file}: {e}"));
        let a = unilateral_analysis::analyze(&p.model, &p.settings)
            .unwrap_or_else(|e| panic!("{file}: {e}"));
        let s = &a.solution;
        assert!(
            matches!(s.outcome, Outcome::Ray { .. } | Outcome::ReturnedToZero),
            "{file}: {:?}",
            s.outcome
        );
        assert!(s.beyond_double_precision().is_none(), "{file}: refused");
        let why = s
            .ending_beyond_double_precision()
            .unwrap_or_else(|| panic!("{file}: no doubt said"));
        assert!(
            why.contains("cannot be resolved in double precision"),
            "{why}"
        );
        assert!(
            s.reading().contains("this ending is in doubt"),
            "{}",
            s.reading()
        );
        let n: f64 = s.pairs.iter().map(|r| r.x_n).sum::<f64>() / force;
        let t: f64 = s.pairs.iter().map(|r| r.x_t).sum::<f64>() / force;
        assert!(
            (n - weight).abs() <= 1e-7 * weight,
            "{file}: ΣN = {n}, by hand {weight}"
        );
        assert!(
            (t.abs() - push).abs() <= 1e-6 * push,
            "{file}: ΣT = {t}, by hand {push}"
        );
    }
}
