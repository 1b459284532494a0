//! Reading a file as text, and turning byte offsets into lines and columns.

use std::io::Read;
use std::path::Path;

use crate::error::{InputError, InputErrorKind, Pos};

/// Files larger than this are refused before reading (a contact zone of this size would not
/// fit a dense solver anyway).
pub(crate) const MAX_FILE_BYTES: u64 = 1 << 30;

/// Opens `path` for reading after checking that it is a regular file within the size limit;
/// returns the file and its length.
pub(crate) fn open_file(path: &Path) -> Result<(std::fs::File, u64), InputError> {
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
    if !meta.is_file() {
        // A device, a pipe or a socket: /dev/zero would be read for ever.
        return Err(InputError::at(
            path,
            None,
            InputErrorKind::Io,
            "this is not a regular file (a device, a pipe or a socket?)",
        ));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(too_large(path, meta.len()));
    }
    let file = std::fs::File::open(path).map_err(io_err)?;
    Ok((file, meta.len()))
}

fn too_large(path: &Path, len: u64) -> InputError {
    InputError::at(
        path,
        None,
        InputErrorKind::Io,
        format!("the file has {len} bytes, more than the {MAX_FILE_BYTES} this program reads"),
    )
}

/// Reads `path` as UTF-8 text. A leading byte-order mark is dropped.
pub(crate) fn read_text(path: &Path) -> Result<String, InputError> {
    let (file, len) = open_file(path)?;
    // The file may grow after the size was looked at: read no more than the limit allows.
    let mut bytes = Vec::with_capacity(len as usize);
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| {
            InputError::at(
                path,
                None,
                InputErrorKind::Io,
                format!("cannot read the file: {e}"),
            )
        })?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(too_large(path, bytes.len() as u64));
    }
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
///
/// Every query costs at most one block of [`BLOCK`] bytes, whatever the length of the line,
/// so that a reader asking for the place of each of a million values on one line stays linear
/// in the size of the file (counting characters from the start of the line was quadratic).
pub(crate) struct LineIndex<'a> {
    text: &'a str,
    /// Byte offset of the start of each line.
    starts: Vec<usize>,
    /// `continuations[k]`: UTF-8 continuation bytes in `text[..k * BLOCK]`.
    continuations: Vec<usize>,
}

/// The stride of [`LineIndex`]'s checkpoints, in bytes.
const BLOCK: usize = 256;

/// A byte that continues a multi-byte UTF-8 character (it starts no character).
fn is_continuation(b: u8) -> bool {
    b & 0xC0 == 0x80
}

impl<'a> LineIndex<'a> {
    pub(crate) fn new(text: &'a str) -> Self {
        let bytes = text.as_bytes();
        let mut starts = vec![0];
        starts.extend(
            bytes
                .iter()
                .enumerate()
                .filter(|&(_, &b)| b == b'\n')
                .map(|(i, _)| i + 1),
        );
        let mut continuations = Vec::with_capacity(bytes.len() / BLOCK + 1);
        let mut count = 0;
        continuations.push(0);
        for block in bytes.chunks(BLOCK) {
            count += block.iter().filter(|&&b| is_continuation(b)).count();
            continuations.push(count);
        }
        Self {
            text,
            starts,
            continuations,
        }
    }

    /// Continuation bytes in `text[..offset]`.
    fn continuations_before(&self, offset: usize) -> usize {
        let block = offset / BLOCK;
        let from = block * BLOCK;
        self.continuations[block]
            + self.text.as_bytes()[from..offset]
                .iter()
                .filter(|&&b| is_continuation(b))
                .count()
    }

    pub(crate) fn pos(&self, offset: usize) -> Pos {
        let offset = offset.min(self.text.len());
        let line = match self.starts.binary_search(&offset) {
            Ok(i) => i,
            Err(i) => i - 1,
        };
        let start = self.starts[line];
        // Characters in text[start..offset]: the bytes that start one.
        let col = (offset - start)
            - (self.continuations_before(offset) - self.continuations_before(start));
        Pos {
            line: line + 1,
            col: col + 1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: counting the characters from the start of the line, as a person would.
    fn by_hand(text: &str, offset: usize) -> Pos {
        let before = &text[..offset];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        Pos {
            line,
            col: before[line_start..].chars().count() + 1,
        }
    }

    #[test]
    fn positions_match_counting_by_hand() {
        // Multi-byte characters on both sides of block boundaries, long and short lines.
        let mut text = String::new();
        for i in 0..40 {
            text.push_str(&"é€x".repeat(i * 7));
            text.push_str("ab\n");
            text.push_str(&"𝄞".repeat(i));
            text.push('\n');
        }
        let index = LineIndex::new(&text);
        for (offset, _) in text.char_indices().chain([(text.len(), ' ')]) {
            assert_eq!(index.pos(offset), by_hand(&text, offset), "offset {offset}");
        }
    }
}
