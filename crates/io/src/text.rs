//! Reading a file as text, and turning byte offsets into lines and columns.

use std::path::Path;

use crate::error::{InputError, InputErrorKind, Pos};

/// Files larger than this are refused before reading (a contact zone of this size would not
/// fit a dense solver anyway).
const MAX_FILE_BYTES: u64 = 1 << 30;

/// Reads `path` as UTF-8 text. A leading byte-order mark is dropped.
pub(crate) fn read_text(path: &Path) -> Result<String, InputError> {
    let io_err = |e: std::io::Error| {
        InputError::at(
            path,
            None,
            InputErrorKind::Io,
            format!("cannot read the file: {e}"),
        )
    };
    let meta = std::fs::metadata(path).map_err(io_err)?;
    if meta.is_dir() {
        return Err(InputError::at(
            path,
            None,
            InputErrorKind::Io,
            "this is a directory, not a file",
        ));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(InputError::at(
            path,
            None,
            InputErrorKind::Io,
            format!(
                "the file has {} bytes, more than the {} this program reads",
                meta.len(),
                MAX_FILE_BYTES
            ),
        ));
    }
    let bytes = std::fs::read(path).map_err(io_err)?;
    decode(path, bytes)
}

/// UTF-8 decoding with the place of the first invalid byte.
pub(crate) fn decode(path: &Path, bytes: Vec<u8>) -> Result<String, InputError> {
    match String::from_utf8(bytes) {
        Ok(mut s) => {
            if s.starts_with('\u{feff}') {
                s.drain(..'\u{feff}'.len_utf8());
            }
            Ok(s)
        }
        Err(e) => {
            let good = e.utf8_error().valid_up_to();
            let bytes = e.as_bytes();
            // The valid prefix is text: count lines and columns in it.
            let prefix = std::str::from_utf8(&bytes[..good]).unwrap_or("");
            let pos = LineIndex::new(prefix).pos(prefix.len());
            let byte = bytes.get(good).copied().unwrap_or(0);
            Err(InputError::at(
                path,
                Some(pos),
                InputErrorKind::Encoding,
                format!(
                    "the file is not UTF-8 text (byte 0x{byte:02x} at offset {good}); is it a binary file?"
                ),
            ))
        }
    }
}

/// Byte offset → 1-based line and column (in characters).
pub(crate) struct LineIndex<'a> {
    text: &'a str,
    /// Byte offset of the start of each line.
    starts: Vec<usize>,
}

impl<'a> LineIndex<'a> {
    pub(crate) fn new(text: &'a str) -> Self {
        let mut starts = vec![0];
        starts.extend(
            text.bytes()
                .enumerate()
                .filter(|&(_, b)| b == b'\n')
                .map(|(i, _)| i + 1),
        );
        Self { text, starts }
    }

    pub(crate) fn pos(&self, offset: usize) -> Pos {
        let offset = offset.min(self.text.len());
        let line = match self.starts.binary_search(&offset) {
            Ok(i) => i,
            Err(i) => i - 1,
        };
        let start = self.starts[line];
        // Offsets given by parsers are char boundaries; be safe anyway.
        let col = self
            .text
            .get(start..offset)
            .map(|s| s.chars().count())
            .unwrap_or(offset - start);
        Pos {
            line: line + 1,
            col: col + 1,
        }
    }
}

/// A whitespace-separated word and where it starts.
pub(crate) struct Word<'a> {
    pub text: &'a str,
    pub pos: Pos,
}

/// The words of one line (`line_no` is 1-based), with their columns counted in characters.
pub(crate) fn words(line: &str, line_no: usize) -> Vec<Word<'_>> {
    let mut out = Vec::new();
    let mut start: Option<(usize, usize)> = None; // (byte, char column)
    let mut col = 0;
    for (i, c) in line.char_indices() {
        col += 1;
        if c.is_whitespace() {
            if let Some((s, sc)) = start.take() {
                out.push(Word {
                    text: &line[s..i],
                    pos: Pos {
                        line: line_no,
                        col: sc,
                    },
                });
            }
        } else if start.is_none() {
            start = Some((i, col));
        }
    }
    if let Some((s, sc)) = start {
        out.push(Word {
            text: &line[s..],
            pos: Pos {
                line: line_no,
                col: sc,
            },
        });
    }
    out
}
