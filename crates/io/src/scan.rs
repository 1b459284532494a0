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

/// The scanner: one block buffer, the place of the next byte, and the counters that give
/// every word its line and column.
pub(crate) struct Scanner<'a> {
    path: &'a Path,
    reader: Box<dyn Read + 'a>,
    /// The file's length as found when it was opened (for size estimates).
    len: u64,
    buf: Vec<u8>,
    /// Next byte to look at.
    at: usize,
    /// Bytes of `buf` known to be whole UTF-8 characters.
    valid: usize,
    /// Bytes of `buf` filled.
    end: usize,
    /// The reader has no more bytes.
    eof: bool,
    /// An invalid UTF-8 byte at this index of `buf` (the scan stops there with an error).
    bad: Option<usize>,
    /// File offset of `buf[0]`.
    base: u64,
    /// Total bytes read (for the size limit).
    read: u64,
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
            buf: vec![0; BLOCK],
            at: 0,
            valid: 0,
            end: 0,
            eof: false,
            bad: None,
            base: 0,
            read: 0,
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
    pub(crate) fn is_empty(&mut self) -> Result<bool, InputError> {
        self.start()?;
        Ok(!self.any)
    }

    /// The file's length in bytes and the offset of the next byte, for bounds on what the rest
    /// of the file can hold.
    pub(crate) fn remaining_bytes(&self) -> u64 {
        self.len.saturating_sub(self.base + self.at as u64)
    }

    fn io_error(&self, e: std::io::Error) -> InputError {
        InputError::at(
            self.path,
            None,
            InputErrorKind::Io,
            format!("cannot read the file: {e}"),
        )
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
    fn start(&mut self) -> Result<(), InputError> {
        if self.started {
            return Ok(());
        }
        self.started = true;
        while self.end < 3 && !self.eof {
            self.fill()?;
        }
        if self.buf[..self.end].starts_with("\u{feff}".as_bytes()) {
            // The mark is not part of the text: columns and offsets start after it, as in
            // `text::decode`.
            self.buf.copy_within(3..self.end, 0);
            self.end -= 3;
            self.valid = self.valid.saturating_sub(3);
            if let Some(b) = &mut self.bad {
                *b -= 3;
            }
            self.bom = true;
            self.validate();
        }
        self.any = self.end > 0;
        Ok(())
    }

    /// Moves the unread bytes to the front and reads more; returns whether bytes were added.
    fn fill(&mut self) -> Result<bool, InputError> {
        if self.eof {
            return Ok(false);
        }
        if self.at > 0 {
            self.buf.copy_within(self.at..self.end, 0);
            self.base += self.at as u64;
            self.valid -= self.at;
            self.end -= self.at;
            if let Some(b) = &mut self.bad {
                *b -= self.at;
            }
            self.at = 0;
        }
        if self.end == self.buf.len() {
            // A word longer than the buffer: grow it (the file's size limit bounds this).
            self.buf.resize(self.buf.len() * 2, 0);
        }
        let n = loop {
            match self.reader.read(&mut self.buf[self.end..]) {
                Ok(n) => break n,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(self.io_error(e)),
            }
        };
        self.read += n as u64;
        if self.read > MAX_FILE_BYTES {
            return Err(InputError::at(
                self.path,
                None,
                InputErrorKind::Io,
                format!("the file has more than the {MAX_FILE_BYTES} bytes this program reads"),
            ));
        }
        self.end += n;
        if n == 0 {
            self.eof = true;
        }
        self.validate();
        Ok(n > 0)
    }

    /// Extends `valid` over the whole characters of `buf[valid..end]`; marks the first
    /// invalid byte.
    fn validate(&mut self) {
        if self.bad.is_some() {
            return;
        }
        match std::str::from_utf8(&self.buf[self.valid..self.end]) {
            Ok(_) => self.valid = self.end,
            Err(e) => {
                let upto = self.valid + e.valid_up_to();
                self.valid = upto;
                // An incomplete character at the end of the block waits for the next block,
                // unless the file ends there.
                if e.error_len().is_some() || self.eof {
                    self.bad = Some(upto);
                }
            }
        }
    }

    /// The error for the invalid byte at the scan's place.
    fn encoding_error(&self) -> InputError {
        // Offsets and the first line's columns count the byte-order mark here, as the
        // in-memory decoder (which looks at the bytes before dropping the mark) does.
        let mark = if self.bom { 3 } else { 0 };
        let offset = self.base + self.at as u64 + mark;
        let mut pos = self.here();
        if self.bom && pos.line == 1 {
            pos.col += 1;
        }
        InputError::at(
            self.path,
            Some(pos),
            InputErrorKind::Encoding,
            format!(
                "the file is not UTF-8 text (byte 0x{:02x} at offset {offset}); is it a binary file?",
                self.buf[self.at]
            ),
        )
    }

    /// Ensures a whole character is available at `at`: `Ok(false)` at the end of the file.
    fn ensure(&mut self) -> Result<bool, InputError> {
        while self.at >= self.valid {
            if self.bad == Some(self.at) {
                return Err(self.encoding_error());
            }
            if !self.fill()? {
                if self.bad == Some(self.at) {
                    return Err(self.encoding_error());
                }
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// The character at `at` (a whole one is available) and its length in bytes.
    fn char_at(&self) -> (char, usize) {
        let b = self.buf[self.at];
        if b < 0x80 {
            return (b as char, 1);
        }
        let len = match b {
            0xC0..=0xDF => 2,
            0xE0..=0xEF => 3,
            _ => 4,
        };
        let s = std::str::from_utf8(&self.buf[self.at..self.at + len]).unwrap_or("\u{fffd}");
        (s.chars().next().unwrap_or('\u{fffd}'), len)
    }

    /// Steps over one character at `at` (available), keeping the line counters.
    fn advance(&mut self, c: char, len: usize) {
        self.at += len;
        if c == '\n' {
            self.line += 1;
            self.line_start = self.base + self.at as u64;
            self.line_continuations = 0;
            self.new_line = true;
        } else {
            self.line_continuations += len as u64 - 1;
        }
    }

    /// Skips white space; `Ok(false)` at the end of the file.
    fn skip_space(&mut self) -> Result<bool, InputError> {
        self.start()?;
        loop {
            // The fast path: ASCII white space within the valid bytes.
            while self.at < self.valid {
                let b = self.buf[self.at];
                if b == b'\n' {
                    self.advance('\n', 1);
                } else if is_ascii_space(b) {
                    self.at += 1;
                } else if b < 0x80 {
                    return Ok(true);
                } else {
                    let (c, len) = self.char_at();
                    if !c.is_whitespace() {
                        return Ok(true);
                    }
                    self.advance(c, len);
                }
            }
            if !self.ensure()? {
                return Ok(false);
            }
        }
    }

    /// Whether a next word exists and starts a new line: `None` at the end of the file.
    /// The word is not consumed.
    pub(crate) fn peek_first_on_line(&mut self) -> Result<Option<bool>, InputError> {
        Ok(self.skip_space()?.then_some(self.new_line))
    }

    /// The first byte of the next word, after a `peek_*` call found one.
    pub(crate) fn peek_byte(&self) -> Option<u8> {
        (self.at < self.valid).then(|| self.buf[self.at])
    }

    /// The line of the next word (`None` at the end of the file). The word is not consumed.
    pub(crate) fn peek_line(&mut self) -> Result<Option<usize>, InputError> {
        Ok(self.skip_space()?.then_some(self.line))
    }

    /// The next word, or `None` at the end of the file.
    pub(crate) fn next_word(&mut self) -> Result<Option<Token<'_>>, InputError> {
        if !self.skip_space()? {
            return Ok(None);
        }
        let pos = self.here();
        self.new_line = false;
        let mut start = self.at;
        let mut i = self.at;
        loop {
            // The fast path over ASCII bytes of the word.
            while i < self.valid {
                let b = self.buf[i];
                if b < 0x80 {
                    if is_ascii_space(b) {
                        break;
                    }
                    i += 1;
                } else {
                    self.at = i;
                    let (c, len) = self.char_at();
                    if c.is_whitespace() {
                        break;
                    }
                    self.line_continuations += len as u64 - 1;
                    i += len;
                }
            }
            if i < self.valid {
                break;
            }
            // The word may go on in the next block: keep its bytes.
            self.at = start;
            let offset = i - start;
            if self.bad == Some(i) {
                self.at = i;
                return Err(self.encoding_error());
            }
            let more = self.fill()?;
            start = self.at;
            i = start + offset;
            if !more {
                if self.bad == Some(i) {
                    self.at = i;
                    return Err(self.encoding_error());
                }
                break;
            }
        }
        self.at = i;
        self.last = Some(pos);
        // `buf[start..i]` lies within the validated bytes.
        let text = std::str::from_utf8(&self.buf[start..i]).unwrap_or("");
        Ok(Some(Token { text, pos }))
    }

    /// Skips the rest of the current line (a comment).
    pub(crate) fn skip_line(&mut self) -> Result<(), InputError> {
        loop {
            while self.at < self.valid {
                let b = self.buf[self.at];
                if b == b'\n' {
                    self.advance('\n', 1);
                    return Ok(());
                }
                if b < 0x80 {
                    self.at += 1;
                } else {
                    let (c, len) = self.char_at();
                    self.advance(c, len);
                }
            }
            if !self.ensure()? {
                return Ok(());
            }
        }
    }

    /// Reads to the end and returns the number of lines as [`str::lines`] counts them, and the
    /// number of words met on the way.
    pub(crate) fn finish(&mut self) -> Result<(usize, usize), InputError> {
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
        s.buf = vec![0; block];
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
            s.buf = vec![0; block];
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
