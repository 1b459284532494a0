//! The structure picture's pair labels, supports and loads, read back from the SVG.

use unilateral_analysis::{analyze, Analysis};
use unilateral_fem::{ContactPairSpec, FrameSection, Load, LoadGroup, Model, SupportDof};
use unilateral_output::structure_svg;

fn picture(model: &Model) -> (Analysis, String) {
    let a = analyze(model, &Default::default()).unwrap();
    let svg = structure_svg(model, &a, &Default::default());
    (a, svg)
}

/// The label boxes (`<rect class="label" x y width height>`) of a picture.
fn label_boxes(svg: &str) -> Vec<[f64; 4]> {
    svg.lines()
        .filter(|l| l.starts_with("<rect class=\"label\""))
        .map(|l| {
            let v = |k: &str| -> f64 {
                l.split(&format!(" {k}=\""))
                    .nth(1)
                    .and_then(|s| s.split('"').next())
                    .unwrap()
                    .parse()
                    .unwrap()
            };
            let (x, y) = (v("x"), v("y"));
            [x, y, x + v("width"), y + v("height")]
        })
        .collect()
}

/// The SVG between `<g class="{class}">` and its `</g>`, for every such group.
fn groups<'a>(svg: &'a str, class: &str) -> Vec<&'a str> {
    let open = format!("<g class=\"{class}\">");
    svg.split(&open)
        .skip(1)
        .map(|s| s.split("</g>").next().unwrap())
        .collect()
}

/// The length of the arrow drawn in a group: its shaft line plus its head (`Svg::arrow`: a
/// head of 7 px on an arrow longer than 11.7 px).
fn arrow_length(group: &str) -> f64 {
    let line = group.lines().find(|l| l.starts_with("<line")).unwrap();
    let v = |k: &str| -> f64 {
        line.split(&format!(" {k}=\""))
            .nth(1)
            .and_then(|s| s.split('"').next())
            .unwrap()
            .parse()
            .unwrap()
    };
    (v("x2") - v("x1")).hypot(v("y2") - v("y1")) + 7.0
}

/// A beam of `n` elements of length 1 on the x axis held by `pairs` frictional pairs with the
/// ground, evenly spaced, and pushed down at its middle.
fn beam_on_pairs(n: usize, pairs: usize) -> Model {
    let mut model = Model::new();
    let nodes: Vec<_> = (0..=n).map(|i| model.add_node(i as f64, 0.0)).collect();
    for w in nodes.windows(2) {
        model.add_frame(w[0], w[1], FrameSection::new(1.0e3, 1.0, 1.0));
    }
    for k in 0..pairs {
        let i = k * n / (pairs - 1).max(1);
        model.add_contact_pair(
            ContactPairSpec::to_ground(nodes[i], [0.0, 1.0])
                .friction(0.5)
                .name(format!("pad {}", k + 1)),
        );
    }
    model.add_load(
        LoadGroup::Variable,
        Load::Nodal {
            node: nodes[n / 2],
            fx: 0.0,
            fy: -1.0,
            m: 0.0,
        },
    );
    model
}

/// Three pairs 2 m apart on a 4 m beam, drawn about 760 px wide (about 190 px a metre, so
/// about 380 px between the pairs — hand calculation), leave room for every name: all three
/// are drawn, and the legend says so.
#[test]
fn few_pairs_are_all_labelled() {
    let (_, svg) = picture(&beam_on_pairs(4, 3));
    for k in 1..=3 {
        assert!(svg.contains(&format!("pad {k}")), "pad {k}");
    }
    assert_eq!(label_boxes(&svg).len(), 3);
    assert!(svg.contains("every pair labelled with its name"));
}

/// 1000 pairs on a beam drawn about 760 px wide (less than a pixel apart): the labels that are
/// drawn do not overlap one another (checked box by box), the others are left out, and the
/// legend counts those left out exactly (1000 − the boxes drawn).
#[test]
fn many_pairs_keep_labels_apart_and_count_the_rest() {
    let (_, svg) = picture(&beam_on_pairs(999, 1000));
    // UNILATERAL_REPORT_OUT=DIR keeps the picture to look at (as the examples' test does).
    if let Some(dir) = std::env::var_os("UNILATERAL_REPORT_OUT") {
        let dir = std::path::Path::new(&dir).join("beam-1000-pairs");
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("structure.svg"), &svg).unwrap();
    }
    let boxes = label_boxes(&svg);
    assert!(
        !boxes.is_empty() && boxes.len() < 50,
        "{} labels",
        boxes.len()
    );
    for (i, a) in boxes.iter().enumerate() {
        for b in &boxes[i + 1..] {
            let overlap = a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
            assert!(!overlap, "{a:?} and {b:?}");
        }
    }
    let said = format!(
        "{} of 1000 pair names left out where they would cover something or sit as near another pair",
        1000 - boxes.len()
    );
    assert!(svg.contains(&said), "{said}");
}

/// A frame clamped at its left end, pinned at the middle, on a roller at the right end (one
/// symbol of each kind, named in the legend), with a constant and a variable nodal force and a
/// moment: each drawn once in its group's colour. The variable force (1 × p) is the largest,
/// drawn 56 px long; the constant one, 1000 times smaller, at the shortest length of 14 px
/// (the documented scale: `LOAD_ARROW`, `MIN_ARROW`).
#[test]
fn supports_and_loads_are_drawn_by_kind_and_group() {
    let mut model = Model::new();
    let nodes: Vec<_> = (0..5).map(|i| model.add_node(i as f64, 0.0)).collect();
    for w in nodes.windows(2) {
        model.add_frame(w[0], w[1], FrameSection::new(1.0e3, 1.0, 1.0));
    }
    model.fix(nodes[0]);
    model.pin(nodes[2]);
    model.add_support(nodes[4], SupportDof::Uy);
    model.add_contact_pair(ContactPairSpec::to_ground(nodes[3], [0.0, 1.0]).friction(0.3));
    model.add_load(
        LoadGroup::Constant,
        Load::Nodal {
            node: nodes[1],
            fx: 0.0,
            fy: -0.001,
            m: 0.0,
        },
    );
    model.add_load(
        LoadGroup::Variable,
        Load::Nodal {
            node: nodes[3],
            fx: 0.0,
            fy: -1.0,
            m: 0.5,
        },
    );
    let (a, svg) = picture(&model);
    assert_eq!(a.solution.p, Some(1.0));
    for (class, count) in [
        ("support fixed", 1),
        ("support pinned", 1),
        ("support roller", 1),
        ("load constant force", 1),
        ("load variable force", 1),
        ("load variable moment", 1),
        ("load constant moment", 0),
    ] {
        assert_eq!(groups(&svg, class).len(), count, "{class}");
    }
    let long = arrow_length(groups(&svg, "load variable force")[0]);
    let short = arrow_length(groups(&svg, "load constant force")[0]);
    assert!((long - 56.0).abs() < 0.05, "{long}");
    assert!((short - 14.0).abs() < 0.05, "{short}");
    for word in [
        "fixed",
        "pinned",
        "roller",
        "constant load",
        "variable load p·F",
    ] {
        assert!(
            svg.contains(&format!("<title>{word}</title>")) || svg.contains(&format!(">{word}<")),
            "{word}"
        );
    }
}

/// A nodal force into a paired node is drawn over the pair's symbol (its head, 3 px from the
/// node, lay under the symbol drawn after it, 7 px away along the normal: a line with no head).
/// Reference: the order of the SVG: the load's group after the last symbol (the beam's pads,
/// the middle one loaded).
#[test]
fn a_load_into_a_paired_node_is_drawn_over_its_symbol() {
    let (_, svg) = picture(&beam_on_pairs(4, 3));
    let load = svg
        .find("<g class=\"load variable force\">")
        .expect("the load's arrow");
    // the pairs' symbols (squares, circles, triangles) come before their name labels (the
    // legend's, after them, are not the pairs')
    let labels = svg.find("<rect class=\"label\"").expect("labels");
    // (squares and circles: the triangles' polygons are like the arrows' heads)
    let last_symbol = ["<rect x=", "<circle"]
        .iter()
        .filter_map(|m| svg[..labels].rfind(m))
        .max()
        .unwrap();
    assert!(
        load > last_symbol && load < labels,
        "the load's arrow is drawn before a pair symbol"
    );
}
