//! The binary ParaView files (`VtkFormat::Binary`, `Compressed` by zlib, `Lz4`) decoded by a
//! reader written here from the VTK XML file format (the `offset` of each appended array, its
//! `UInt64` byte count or compressed block header, the little-endian values; zlib blocks
//! inflated by `miniz_oxide`, another implementation than the writer's own encoder, LZ4 blocks
//! by [`lz4_block`], written here from the LZ4 block format, not the writer's `lz4_flex`)
//! and compared value for value with the ascii files of the same run — the reference: the
//! ascii writer's numbers read back to the same `f64` (Rust's shortest round trip), checked
//! against the analysis by `vtk.rs`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use unilateral_analysis::{analyze, analyze_history};
use unilateral_io::{read_problem, Problem, StructuralProblem};
use unilateral_output::{history_vtk_with, write_vtk_with, VtkFormat, COMPRESSED_BLOCK};

fn problem(name: &str) -> StructuralProblem {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    let Problem::Structural(p) = read_problem(&path).unwrap() else {
        panic!("{name} is not a structural model");
    };
    p
}

/// An LZ4 block decoded, from the block format's description (lz4's `lz4_Block_format.md`):
/// sequences of a token (literal count in the high four bits, match length − 4 in the low
/// four, each 15 continued by bytes up to a byte below 255), the literals, and a two-byte
/// little-endian offset back into the output; the last sequence has literals only. Panics on
/// a malformed block (a test's failure).
fn lz4_block(src: &[u8], expect: usize) -> Vec<u8> {
    let mut out: Vec<u8> = Vec::with_capacity(expect);
    let mut i = 0;
    let length = |i: &mut usize, mut n: usize| {
        if n == 15 {
            loop {
                let b = src[*i];
                *i += 1;
                n += usize::from(b);
                if b != 255 {
                    break;
                }
            }
        }
        n
    };
    loop {
        let token = src[i];
        i += 1;
        let literals = length(&mut i, usize::from(token >> 4));
        out.extend_from_slice(&src[i..i + literals]);
        i += literals;
        if i == src.len() {
            break;
        }
        let offset = usize::from(u16::from_le_bytes([src[i], src[i + 1]]));
        i += 2;
        assert!(offset > 0 && offset <= out.len(), "offset {offset}");
        let len = length(&mut i, usize::from(token & 15)) + 4;
        // Byte by byte: a match may overlap the bytes it copies.
        let from = out.len() - offset;
        for k in 0..len {
            let b = out[from + k];
            out.push(b);
        }
    }
    assert_eq!(out.len(), expect);
    out
}

/// The value of attribute `key` in the tag text `tag` (`<DataArray type="…" …`).
fn attr<'a>(tag: &'a str, key: &str) -> Option<&'a str> {
    let at = tag.find(&format!(" {key}=\""))? + key.len() + 3;
    tag[at..].split('"').next()
}

/// Every data array of a `.vtu` file by name (within its section, `PointData/x`), each as its
/// values in order. Ascii arrays are parsed from their text; appended arrays are decoded
/// from the bytes after `<AppendedData encoding="raw">`'s `_`.
fn arrays(bytes: &[u8]) -> BTreeMap<String, Vec<f64>> {
    // The XML part is text up to the appended data.
    let marker = b"<AppendedData encoding=\"raw\">";
    let split = bytes
        .windows(marker.len())
        .position(|w| w == marker)
        .unwrap_or(bytes.len());
    let xml = std::str::from_utf8(&bytes[..split]).expect("the XML part is UTF-8");
    let data: &[u8] = if split < bytes.len() {
        let rest = &bytes[split + marker.len()..];
        let us = rest.iter().position(|&b| b == b'_').expect("the '_' mark");
        assert!(rest[..us].iter().all(u8::is_ascii_whitespace));
        &rest[us + 1..]
    } else {
        &[]
    };
    let header = xml.lines().nth(1).unwrap();
    let compressor = attr(header, "compressor");
    let compressed = compressor.is_some();
    if !data.is_empty() {
        assert_eq!(attr(header, "header_type"), Some("UInt64"), "{header}");
    }
    let u64_at = |at: usize| u64::from_le_bytes(data[at..at + 8].try_into().unwrap()) as usize;
    let mut out = BTreeMap::new();
    let mut section = String::new();
    for (k, piece) in xml.split('<').enumerate().skip(1) {
        let tag = piece.split('>').next().unwrap();
        let name = tag.split([' ', '/']).next().unwrap();
        if ["PointData", "CellData", "FieldData", "Points", "Cells"].contains(&name) {
            section = name.to_string();
        }
        if name != "DataArray" {
            continue;
        }
        let key = format!("{section}/{}", attr(tag, "Name").unwrap());
        let ty = attr(tag, "type").unwrap();
        let values: Vec<f64> = match attr(tag, "format").unwrap() {
            "ascii" => piece
                .split_once('>')
                .unwrap()
                .1
                .split_ascii_whitespace()
                .map(|w| w.parse().unwrap())
                .collect(),
            "appended" => {
                let at: usize = attr(tag, "offset").unwrap().parse().unwrap();
                let raw = if compressed {
                    let blocks = u64_at(at);
                    let (size, partial) = (u64_at(at + 8), u64_at(at + 16));
                    assert_eq!(size, COMPRESSED_BLOCK);
                    let mut start = at + 24 + 8 * blocks;
                    let mut raw = Vec::new();
                    for b in 0..blocks {
                        let csize = u64_at(at + 24 + 8 * b);
                        let expect = if b + 1 == blocks && partial > 0 {
                            partial
                        } else {
                            size
                        };
                        let bytes = &data[start..start + csize];
                        let block = match compressor {
                            Some("vtkZLibDataCompressor") => {
                                miniz_oxide::inflate::decompress_to_vec_zlib(bytes).unwrap()
                            }
                            Some("vtkLZ4DataCompressor") => lz4_block(bytes, expect),
                            c => panic!("compressor {c:?}"),
                        };
                        assert_eq!(block.len(), expect, "{key}: block {b}");
                        raw.extend(block);
                        start += csize;
                    }
                    raw
                } else {
                    let n = u64_at(at);
                    data[at + 8..at + 8 + n].to_vec()
                };
                let width = match ty {
                    "Float64" | "Int64" => 8,
                    "Int32" => 4,
                    "UInt8" => 1,
                    _ => panic!("type {ty}"),
                };
                assert_eq!(raw.len() % width, 0, "{key}");
                raw.chunks(width)
                    .map(|c| match ty {
                        "Float64" => f64::from_le_bytes(c.try_into().unwrap()),
                        "Int64" => i64::from_le_bytes(c.try_into().unwrap()) as f64,
                        "Int32" => f64::from(i32::from_le_bytes(c.try_into().unwrap())),
                        _ => f64::from(c[0]),
                    })
                    .collect()
            }
            f => panic!("format {f} (tag {k})"),
        };
        assert!(out.insert(key.clone(), values).is_none(), "{key} twice");
    }
    out
}

/// The files of the four formats agree: the same names, and every `.vtu` holds the same
/// arrays with the same values (bit for bit); the `.pvd` is the same text. Returns the number
/// of `.vtu` files compared.
fn same_in_every_format(files: &dyn Fn(VtkFormat) -> Vec<(String, Vec<u8>)>) -> usize {
    let ascii = files(VtkFormat::Ascii);
    let mut compared = 0;
    for format in [VtkFormat::Binary, VtkFormat::Compressed, VtkFormat::Lz4] {
        let other = files(format);
        let names = |f: &[(String, Vec<u8>)]| f.iter().map(|x| x.0.clone()).collect::<Vec<_>>();
        assert_eq!(names(&ascii), names(&other));
        for ((name, a), (_, b)) in ascii.iter().zip(&other) {
            if name.ends_with(".pvd") {
                assert_eq!(a, b, "{name}");
                continue;
            }
            let text = std::str::from_utf8(a).unwrap();
            assert!(!text.contains("format=\"appended\""), "{name}");
            let appended = b"format=\"appended\"";
            assert!(
                b.windows(appended.len()).any(|w| w == appended),
                "{name} ({format:?}) has appended data"
            );
            let (va, vb) = (arrays(a), arrays(b));
            assert_eq!(
                va.keys().collect::<Vec<_>>(),
                vb.keys().collect::<Vec<_>>(),
                "{name}"
            );
            for (key, x) in &va {
                let y = &vb[key];
                assert_eq!(x.len(), y.len(), "{name} {key}");
                for (i, (u, v)) in x.iter().zip(y).enumerate() {
                    assert_eq!(u.to_bits(), v.to_bits(), "{name} {key}[{i}]: {u} vs {v}");
                }
            }
            compared += 1;
        }
    }
    compared
}

fn read_dir(dir: &Path, files: &[PathBuf]) -> Vec<(String, Vec<u8>)> {
    files
        .iter()
        .map(|f| {
            assert_eq!(f.parent(), Some(dir));
            let name = f.file_name().unwrap().to_string_lossy().into_owned();
            (name, std::fs::read(f).unwrap())
        })
        .collect()
}

/// The path of the cantilever on its plane-element foundation (frames, plane elements,
/// pairs: every kind of array), the sheet pile wall and the cylinder on its foundation (pairs
/// whose A point lies on a segment, between two nodes), in the four formats.
#[test]
fn binary_and_compressed_files_decode_to_the_ascii_values() {
    for name in [
        "example2-cantilever.toml",
        "sheet-pile-wall.toml",
        "cylinder-on-foundation.toml",
    ] {
        let p = problem(name);
        let a = analyze(&p.model, &p.settings).unwrap();
        let tmp = tempfile::tempdir().unwrap();
        let files = |format: VtkFormat| {
            let dir = tmp.path().join(format!("{format:?}"));
            let written = write_vtk_with(&a, &dir, format).unwrap();
            read_dir(&dir, &written)
        };
        assert!(same_in_every_format(&files) >= 8, "{name}");
    }
}

/// The deck on sliding bearings (a structural history), in the four formats.
#[test]
fn history_binary_files_decode_to_the_ascii_values() {
    let p = problem("deck-bearings-temperature.toml");
    let stages = p.history.clone().expect("a history");
    let a = analyze_history(&p.model, &stages, &p.settings.engine).unwrap();
    let files = |format: VtkFormat| history_vtk_with(&a, format).unwrap();
    assert!(same_in_every_format(&files) >= 8);
}

/// Exactly one state of the path is marked `reported` (field data 1; every other file 0),
/// and it is the one at the reported load `p`.
#[test]
fn the_reported_state_is_marked() {
    let p = problem("example2-cantilever.toml");
    let a = analyze(&p.model, &p.settings).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let written = write_vtk_with(&a, tmp.path(), VtkFormat::Compressed).unwrap();
    let mut marked = Vec::new();
    for (name, bytes) in read_dir(tmp.path(), &written) {
        if name.ends_with(".pvd") {
            continue;
        }
        let v = arrays(&bytes);
        let flag = v["FieldData/reported"][0];
        assert!(flag == 0.0 || flag == 1.0, "{name}");
        if flag == 1.0 {
            marked.push((name, v["FieldData/TimeValue"][0]));
        }
    }
    let reported = a.p().unwrap();
    assert_eq!(marked.len(), 2, "a mesh and a pairs file: {marked:?}");
    assert!(marked.iter().all(|(_, t)| *t == reported), "{marked:?}");
}

/// An array longer than one compressed block is split into blocks with a partial last one (the
/// header's third number), and decodes in both compressions: the points of a beam of 1500
/// nodes (36 000 bytes, two blocks) are the model's coordinates. Reference: the model's own
/// node list.
#[test]
fn long_arrays_span_several_compressed_blocks() {
    use unilateral_fem::{ContactPairSpec, FrameSection, Load, LoadGroup, Model};
    let mut model = Model::new();
    let n = 1500;
    let nodes: Vec<_> = (0..n).map(|i| model.add_node(i as f64, 0.0)).collect();
    for w in nodes.windows(2) {
        model.add_frame(w[0], w[1], FrameSection::new(1.0, 2.0, 1.0));
    }
    // A continuous beam pinned at every tenth node, on three frictional pairs between.
    for i in (0..n).step_by(10) {
        model.pin(nodes[i]);
    }
    for &i in &[nodes[5], nodes[15], nodes[25]] {
        model.add_contact_pair(ContactPairSpec::to_ground(i, [0.0, 1.0]).friction(0.5));
    }
    model.add_load(
        LoadGroup::Variable,
        Load::Nodal {
            node: nodes[15],
            fx: 0.1,
            fy: -1.0,
            m: 0.0,
        },
    );
    let a = analyze(&model, &Default::default()).unwrap();
    assert!(24 * n > COMPRESSED_BLOCK && 24 * n % COMPRESSED_BLOCK != 0);
    for (format, compressor) in [
        (VtkFormat::Compressed, "vtkZLibDataCompressor"),
        (VtkFormat::Lz4, "vtkLZ4DataCompressor"),
    ] {
        let tmp = tempfile::tempdir().unwrap();
        let written = write_vtk_with(&a, tmp.path(), format).unwrap();
        let mesh = std::fs::read(&written[0]).unwrap();
        let tag = format!("compressor=\"{compressor}\"");
        assert!(mesh.windows(tag.len()).any(|w| w == tag.as_bytes()));
        let v = arrays(&mesh);
        let points = &v["Points/Points"];
        assert_eq!(points.len(), 3 * n);
        for (i, xy) in model.nodes().iter().enumerate() {
            assert_eq!(points[3 * i], xy[0]);
            assert_eq!(points[3 * i + 1], xy[1]);
            assert_eq!(points[3 * i + 2], 0.0);
        }
    }
}
