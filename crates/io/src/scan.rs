//! A streaming word scanner for the large numeric files (`.dat`, `.mtx`).
//!
//! The file is read in blocks of [`BLOCK`] bytes and never held whole: a dense matrix of
//! n = 3000 written as text is about 200 MB, three times the matrix it holds. Each word comes
//! with its line and column (counted in characters, as an editor shows them), computed from
//! counters the scan keeps anyway, so no position has to be stored for later; a reader that
//! needs the place of an entry after the scan (to report a property of the whole matrix) reads
//! the file again on that error path.
//!
//! Words are separated by Unicode white space and lines end at `\n`, exactly as
//! [`str::split_whitespace`] and [`str::lines`] see the text; a leading byte-order mark is
//! skipped. The text must be UTF-8: the first invalid byte is an error at its place, reported
//! when the scan reaches it.

use std::io::Read;
use std::path::Path;

use crate::error::{InputError, InputErrorKind, Pos};
use crate::text::{open_file, MAX_FILE_BYTES};

/// The scanner's results: the error is boxed so that the words of the hot loop move as two
/// machine words, not as a whole [`InputError`].
pub(crate) type Scan<T> = Result<T, Box<InputError>>;

/// Bytes read per block.
const BLOCK: usize = 1 << 20;

/// Where the bytes come from.
#[derive(Clone, Copy)]
pub(crate) enum Source<'a> {
    /// A file on disk, read in blocks.
    File(&'a Path),
    /// Text in memory (the readers' unit tests).
    #[cfg(test)]
    Text(&'a str),
}

impl<'a> Source<'a> {
    /// A scanner from the start of the source; errors name `path`.
    pub(crate) fn scanner(self, path: &'a Path) -> Result<Scanner<'a>, InputError> {
        let (reader, len): (Box<dyn Read + 'a>, u64) = match self {
            Source::File(p) => {
                let (file, len) = open_file(p)?;
                // The file may grow after its size was looked at: read no more than the limit.
                (Box::new(file.take(MAX_FILE_BYTES + 1)), len)
            }
            #[cfg(test)]
            Source::Text(t) => (Box::new(t.as_bytes()), t.len() as u64),
        };
        Ok(Scanner::new(path, reader, len))
    }
}

/// A word of the file and where it starts.
pub(crate) struct Token<'s> {
    /// The word.
    pub text: &'s str,
    /// Its line and column (1-based, columns in characters).
    pub pos: Pos,
}

/// The scanner: the text of the current block, the place of the next character, and the
/// counters that give every word its line and column.
pub(crate) struct Scanner<'a> {
    path: &'a Path,
    reader: Box<dyn Read + 'a>,
    /// The file's length as found when it was opened (for size estimates).
    len: u64,
    /// Validated text of the current block (and of a word that runs on from the last one).
    text: String,
    /// Bytes read but not yet moved into `text`: a character cut by the block's end.
    raw: Vec<u8>,
    /// Next byte of `text` to look at.
    at: usize,
    /// The reader has no more bytes.
    eof: bool,
    /// The byte that follows `text` is not UTF-8: the scan stops there with an error.
    bad: Option<u8>,
    /// File offset of `text[0]`.
    base: u64,
    /// Total bytes read (for the size limit).
    read: u64,
    /// Bytes asked of the reader per read.
    block: usize,
    /// The line of the next byte (1-based).
    line: usize,
    /// File offset of the first byte of the current line.
    line_start: u64,
    /// UTF-8 continuation bytes between `line_start` and the next byte.
    line_continuations: u64,
    /// A line ended since the last word (or no word was read yet).
    new_line: bool,
    /// The last word's place (for "the file ends here" messages).
    last: Option<Pos>,
    /// The file had any byte after the byte-order mark.
    any: bool,
    started: bool,
    /// A byte-order mark was skipped (the encoding error counts it, as `text::decode` does).
    bom: bool,
}

fn is_ascii_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | b'\r' | 0x0b | 0x0c)
}

impl<'a> Scanner<'a> {
    fn new(path: &'a Path, reader: Box<dyn Read + 'a>, len: u64) -> Self {
        Self {
            path,
            reader,
            len,
            text: String::with_capacity(BLOCK),
            raw: Vec::with_capacity(BLOCK),
            at: 0,
            eof: false,
            bad: None,
            base: 0,
            read: 0,
            block: BLOCK,
            line: 1,
            line_start: 0,
            line_continuations: 0,
            new_line: true,
            last: None,
            any: false,
            started: false,
            bom: false,
        }
    }

    /// The place of the last word read, if any.
    pub(crate) fn last(&self) -> Option<Pos> {
        self.last
    }

    /// The file had no byte (after a byte-order mark).
    pub(crate) fn is_empty(&mut self) -> Scan<bool> {
        self.start()?;
        Ok(!self.any)
    }

    /// An upper bound on the bytes after the next one, for bounds on what the rest of the file
    /// can hold.
    pub(crate) fn remaining_bytes(&self) -> u64 {
        self.len.saturating_sub(self.base + self.at as u64)
    }

    fn io_error(&self, e: std::io::Error) -> Box<InputError> {
        Box::new(InputError::at(
            self.path,
            None,
            InputErrorKind::Io,
            format!("cannot read the file: {e}"),
        ))
    }

    /// The place of the next byte.
    fn here(&self) -> Pos {
        let offset = self.base + self.at as u64;
        Pos {
            line: self.line,
            col: (offset - self.line_start - self.line_continuations) as usize + 1,
        }
    }

    /// Reads the first block and skips a byte-order mark.
    #[inline]
    fn start(&mut self) -> Scan<()> {
        if !self.started {
            self.started = true;
            while self.text.len() < 3 && self.fill()? {}
            if self.text.starts_with('\u{feff}') {
                // The mark is not part of the text: columns and offsets start after it, as in
                // `text::decode`.
                self.text.drain(..3);
                self.bom = true;
            }
            self.any = !self.text.is_empty() || self.bad.is_some();
        }
        Ok(())
    }

    /// Drops the text before `at`, reads more and moves its whole characters into `text`;
    /// returns whether text was added.
    fn fill(&mut self) -> Scan<bool> {
        if self.at > 0 {
            self.text.drain(..self.at);
            self.base += self.at as u64;
            self.at = 0;
        }
        let before = self.text.len();
        while self.text.len() == before && !self.eof && self.bad.is_none() {
            let have = self.raw.len();
            self.raw.resize(have + self.block, 0);
            let n = loop {
                match self.reader.read(&mut self.raw[have..]) {
                    Ok(n) => break n,
                    Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                    Err(e) => {
                        self.raw.truncate(have);
                        return Err(self.io_error(e));
                    }
                }
            };
            self.raw.truncate(have + n);
            self.read += n as u64;
            if self.read > MAX_FILE_BYTES {
                return Err(Box::new(InputError::at(
                    self.path,
                    None,
                    InputErrorKind::Io,
                    format!("the file has more than the {MAX_FILE_BYTES} bytes this program reads"),
                )));
            }
            self.eof = n == 0;
            let (good, bad) = match std::str::from_utf8(&self.raw) {
                Ok(t) => {
                    self.text.push_str(t);
                    (self.raw.len(), false)
                }
                Err(e) => {
                    let good = e.valid_up_to();
                    let t = std::str::from_utf8(&self.raw[..good]).unwrap_or_default();
                    self.text.push_str(t);
                    // A character cut by the block's end waits for the next block, unless the
                    // file ends there.
                    (good, e.error_len().is_some() || self.eof)
                }
            };
            if bad {
                self.bad = Some(self.raw[good]);
            }
            self.raw.drain(..good);
        }
        Ok(self.text.len() > before)
    }

    /// The error for the invalid byte that follows the text.
    fn encoding_error(&self) -> Box<InputError> {
        // Offsets and the first line's columns count the byte-order mark here, as the
        // in-memory decoder (which looks at the bytes before dropping the mark) does.
        let mark = if self.bom { 3 } else { 0 };
        let offset = self.base + self.at as u64 + mark;
        let mut pos = self.here();
        if self.bom && pos.line == 1 {
            pos.col += 1;
        }
        Box::new(InputError::at(
            self.path,
            Some(pos),
            InputErrorKind::Encoding,
            format!(
                "the file is not UTF-8 text (byte 0x{:02x} at offset {offset}); is it a binary file?",
                self.bad.unwrap_or(0)
            ),
        ))
    }

    /// Makes text available at `at`: `Ok(false)` at the end of the file.
    fn more(&mut self) -> Scan<bool> {
        if self.fill()? {
            return Ok(true);
        }
        if self.bad.is_some() {
            return Err(self.encoding_error());
        }
        Ok(false)
    }

    /// The character at `at` (a non-ASCII one).
    fn char_at(&self) -> char {
        self.text[self.at..].chars().next().unwrap_or('\u{fffd}')
    }

    /// Skips white space; `Ok(false)` at the end of the file. With `in_line`, stops after the
    /// end of a line as well (returns `Ok(false)` there).
    #[inline]
    fn skip_space(&mut self, in_line: bool) -> Scan<bool> {
        self.start()?;
        loop {
            let bytes = self.text.as_bytes();
            while self.at < bytes.len() {
                let b = bytes[self.at];
                if b == b'\n' {
                    self.at += 1;
                    self.line += 1;
                    self.line_start = self.base + self.at as u64;
                    self.line_continuations = 0;
                    self.new_line = true;
                    if in_line {
                        return Ok(false);
                    }
                } else if is_ascii_space(b) {
                    self.at += 1;
                } else if b < 0x80 {
                    return Ok(true);
                } else {
                    let c = self.char_at();
                    if !c.is_whitespace() {
                        return Ok(true);
                    }
                    let len = c.len_utf8();
                    self.at += len;
                    self.line_continuations += len as u64 - 1;
                }
            }
            if !self.more()? {
                return Ok(false);
            }
        }
    }

    /// Whether a next word exists and starts a new line: `None` at the end of the file.
    /// The word is not consumed.
    pub(crate) fn peek_first_on_line(&mut self) -> Scan<Option<bool>> {
        Ok(self.skip_space(false)?.then_some(self.new_line))
    }

    /// The first byte of the next word, after a `peek_*` call found one.
    pub(crate) fn peek_byte(&self) -> Option<u8> {
        self.text.as_bytes().get(self.at).copied()
    }

    /// The line of the next word (`None` at the end of the file). The word is not consumed.
    pub(crate) fn peek_line(&mut self) -> Scan<Option<usize>> {
        Ok(self.skip_space(false)?.then_some(self.line))
    }

    /// The next word, or `None` at the end of the file.
    pub(crate) fn next_word(&mut self) -> Scan<Option<Token<'_>>> {
        if !self.skip_space(false)? {
            return Ok(None);
        }
        self.word().map(Some)
    }

    /// The next word if it is on the current line; `None` at the end of the line (which is
    /// then consumed) or of the file.
    pub(crate) fn next_on_line(&mut self) -> Scan<Option<Token<'_>>> {
        if self.new_line || !self.skip_space(true)? {
            return Ok(None);
        }
        self.word().map(Some)
    }

    /// The word that starts at `at` (after white space was skipped).
    fn word(&mut self) -> Scan<Token<'_>> {
        let pos = self.here();
        self.new_line = false;
        let mut i = self.at;
        loop {
            let bytes = self.text.as_bytes();
            // The fast path over ASCII bytes of the word.
            while i < bytes.len() {
                let b = bytes[i];
                if b < 0x80 {
                    if is_ascii_space(b) {
                        break;
                    }
                    i += 1;
                } else {
                    let c = self.text[i..].chars().next().unwrap_or(' ');
                    if c.is_whitespace() {
                        break;
                    }
                    let len = c.len_utf8();
                    self.line_continuations += len as u64 - 1;
                    i += len;
                }
            }
            if i < self.text.len() {
                break;
            }
            // The word may go on in the next block: keep its bytes.
            let offset = i - self.at;
            let more = self.fill()?;
            i = self.at + offset;
            if !more {
                if self.bad.is_some() {
                    self.at = i;
                    return Err(self.encoding_error());
                }
                break;
            }
        }
        let start = self.at;
        self.at = i;
        self.last = Some(pos);
        Ok(Token {
            text: &self.text[start..i],
            pos,
        })
    }

    /// The rest of the current line from its next word on, as written (a quoted name with
    /// spaces), without trailing white space; the line's end is consumed. `None` when the
    /// line has no more words.
    pub(crate) fn rest_of_line(&mut self) -> Scan<Option<(String, Pos)>> {
        if self.new_line || !self.skip_space(true)? {
            return Ok(None);
        }
        let pos = self.here();
        self.new_line = false;
        let mut out = String::new();
        loop {
            let end = self.text[self.at..].find('\n').map(|k| self.at + k);
            let stop = end.unwrap_or(self.text.len());
            let piece = &self.text[self.at..stop];
            self.line_continuations += piece.bytes().filter(|&b| b & 0xC0 == 0x80).count() as u64;
            out.push_str(piece);
            self.at = stop;
            if end.is_some() || !self.more()? {
                break;
            }
        }
        self.skip_space(true)?;
        self.last = Some(pos);
        out.truncate(out.trim_end().len());
        Ok(Some((out, pos)))
    }

    /// Skips the rest of the current line (a comment).
    pub(crate) fn skip_line(&mut self) -> Scan<()> {
        loop {
            let bytes = self.text.as_bytes();
            while self.at < bytes.len() {
                let b = bytes[self.at];
                if b == b'\n' {
                    return self.skip_space(true).map(|_| ());
                }
                if b < 0x80 {
                    self.at += 1;
                } else {
                    let len = self.char_at().len_utf8();
                    self.at += len;
                    self.line_continuations += len as u64 - 1;
                }
            }
            if !self.more()? {
                return Ok(());
            }
        }
    }

    /// Reads to the end and returns the number of lines as [`str::lines`] counts them, and the
    /// number of words met on the way.
    pub(crate) fn finish(&mut self) -> Scan<(usize, usize)> {
        let mut words = 0;
        while self.next_word()?.is_some() {
            words += 1;
        }
        // `lines()` counts a last line without its `\n`, and no empty line after a final `\n`.
        let offset = self.base + self.at as u64;
        let lines = if offset > self.line_start {
            self.line
        } else {
            self.line - 1
        };
        Ok((lines, words))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every word with its place, scanned with a tiny block so that words, multi-byte
    /// characters and line ends straddle the block boundary.
    fn scan(text: &str, block: usize) -> Vec<(String, usize, usize, bool)> {
        let path = Path::new("t.dat");
        let mut s = Scanner::new(path, Box::new(text.as_bytes()), text.len() as u64);
        s.block = block;
        let mut out = Vec::new();
        while let Some(first) = s.peek_first_on_line().unwrap() {
            let t = s.next_word().unwrap().unwrap();
            out.push((t.text.to_string(), t.pos.line, t.pos.col, first));
        }
        out
    }

    /// Reference: `str::lines` and `split_whitespace`, with columns counted in characters by
    /// hand, as the in-memory readers did.
    fn by_hand(text: &str) -> Vec<(String, usize, usize, bool)> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut out = Vec::new();
        for (l, line) in text.lines().enumerate() {
            let mut first = true;
            let mut col = 0;
            let mut start = None;
            for c in line.chars().chain([' ']) {
                col += 1;
                if c.is_whitespace() {
                    if let Some((w, sc)) = start.take() {
                        out.push((w, l + 1, sc, first));
                        first = false;
                    }
                } else {
                    match &mut start {
                        Some((w, _)) => String::push(w, c),
                        None => start = Some((c.to_string(), col)),
                    }
                }
            }
        }
        out
    }

    #[test]
    fn words_and_places_match_the_in_memory_split() {
        let text = "\u{feff}3 0\n  3\t3\r\n3 3\n\n1.5e-3 -2 é€x 7\u{a0}8\u{2003}9 𝄞\n  \n% c\nlast";
        for block in [1, 2, 3, 5, 7, 64] {
            assert_eq!(scan(text, block), by_hand(text), "block {block}");
        }
    }

    #[test]
    fn lines_counted_as_str_lines() {
        for text in ["", "a", "a\n", "a\nb", "a\nb\n", "\n", "\n\n", "a\n\n"] {
            let mut s = Scanner::new(Path::new("t"), Box::new(text.as_bytes()), 0);
            let (lines, _) = s.finish().unwrap();
            assert_eq!(lines, text.lines().count(), "{text:?}");
        }
    }

    #[test]
    fn invalid_utf8_is_an_error_at_its_place() {
        // Reference: the in-memory decoder's message and place for the same bytes.
        let bytes = b"12\n0\n\xff\xfe garbage".to_vec();
        let want = crate::text::decode(Path::new("t"), bytes.clone()).unwrap_err();
        for block in [1, 2, 4, 1 << 10] {
            let mut s = Scanner::new(Path::new("t"), Box::new(&bytes[..]), 0);
            s.block = block;
            let got = loop {
                match s.next_word() {
                    Ok(Some(_)) => {}
                    Ok(None) => panic!("no error"),
                    Err(e) => break e,
                }
            };
            assert_eq!(got.to_string(), want.to_string(), "block {block}");
        }
    }
}
