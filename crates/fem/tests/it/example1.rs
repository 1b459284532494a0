//! Example 1 of Popov & Lovtsov (2023): two-span beam held only by three contact pairs.
#![allow(clippy::needless_range_loop)]

use unilateral_fem::{ContactPairSpec, FrameSection, LinkValues, Load, LoadGroup, Model};
use unilateral_oracle::fixtures::example1::{self as ex1, beam};

fn example1() -> Model {
    // spans of 2 m, EI = 1, EA = 2 (L³/EI = 8, EA/L = 1), pairs at x = 0, 2, 4, unit load at 3.
    let mut model = Model::new();
    let n: Vec<_> = beam::NODE_X
        .iter()
        .map(|&x| model.add_node(x, 0.0))
        .collect();
    let section = FrameSection::new(beam::E, beam::AREA, beam::INERTIA);
    for w in n.windows(2) {
        model.add_frame(w[0], w[1], section);
    }
    for i in beam::SUPPORTED_NODES.map(|k| n[k]) {
        model.add_contact_pair(ContactPairSpec::to_ground(i, beam::NORMAL).friction(ex1::FRICTION));
    }
    model.add_load(
        LoadGroup::Variable,
        Load::Nodal {
            node: n[beam::LOADED_NODE],
            fx: 0.0,
            fy: beam::LOAD_FY,
            m: 0.0,
        },
    );
    model
}

#[test]
fn example1_csm_and_clv() {
    let c = example1().condense().unwrap();
    let (rnn, rtt) = (ex1::RNN, ex1::RTT);
    for i in 0..3 {
        for j in 0..3 {
            assert!(
                (c.rnn[(i, j)] - rnn[i][j]).abs() < 1e-12,
                "Rnn[{i}][{j}] = {}",
                c.rnn[(i, j)]
            );
            assert!(
                (c.rtt[(i, j)] - rtt[i][j]).abs() < 1e-12,
                "Rtt[{i}][{j}] = {}",
                c.rtt[(i, j)]
            );
            assert!(c.rnt[(i, j)].abs() < 1e-12);
            assert!(c.rtn[(i, j)].abs() < 1e-12);
        }
    }
    let rv = ex1::RV_N;
    for i in 0..3 {
        assert!(
            (c.variable.normal[i] - rv[i]).abs() < 1e-12,
            "{:?}",
            c.variable
        );
        assert!(c.variable.tangential[i].abs() < 1e-12);
        assert_eq!(c.constant.normal[i], 0.0);
    }
    assert_eq!(c.friction, vec![ex1::FRICTION; 3]);
    assert_eq!(c.pair_names, vec!["1", "2", "3"]);
}

#[test]
fn example1_recovery_of_the_paper_solution() {
    // The paper's answer at p = 1: support 1 lifts by 0.5, the others carry 0.5 each.
    let c = example1().condense().unwrap();
    let sol = LinkValues {
        p: 1.0,
        x_n: ex1::X_AT_TARGET[..3].to_vec(),
        x_t: vec![0.0; 3],
        z_n: ex1::Z_AT_TARGET[..3].to_vec(),
        z_t: vec![0.0; 3],
    };
    let r = c.recover(&sol).unwrap();
    // uplift of the left end = P L³ / (16 EI) = 0.5
    assert!((r.displacements[0][1] - 0.5).abs() < 1e-12);
    let e = &r.equilibrium;
    assert!(e.relative() < 1e-12, "{e:?}");
    assert!((r.link_forces.normal[1] - 0.5).abs() < 1e-12);
    // moment under the load: beam simply supported on 2–4 with P = 1 at mid-span: PL/4 = 0.5
    let m_mid = r.lines[1].diagram.last().unwrap().m;
    assert!((m_mid - 0.5).abs() < 1e-12);
    assert!(
        (r.lines[2].diagram[0].m - 0.5).abs() < 1e-12,
        "{:?}",
        r.lines[2].diagram[0]
    );
}
