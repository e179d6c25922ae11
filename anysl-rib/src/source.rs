//! Source files and locations.
//!
//! Every token, request and parameter carries a [`Loc`]: the file it came from (after
//! `ReadArchive`), its byte range, and its 1-based line and column. The [`SourceMap`] owns the
//! bytes of every file read so that diagnostics can print the source line with a caret.

use std::fmt;
use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

/// Index of a file in a [`SourceMap`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct FileId(pub u32);

/// A place in a RIB file: file, byte range, 1-based line and column.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Loc {
    /// The file's id in the [`SourceMap`].
    pub file: FileId,
    /// The file's name as shown in diagnostics.
    pub name: Arc<str>,
    /// First byte.
    pub start: u32,
    /// One past the last byte.
    pub end: u32,
    /// 1-based line of `start`.
    pub line: u32,
    /// 1-based column (in characters) of `start`.
    pub col: u32,
}

impl fmt::Display for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.name, self.line, self.col)
    }
}

/// One source file (decompressed when it was gzip-compressed).
#[derive(Clone, Debug)]
pub struct SourceFile {
    /// Name shown in diagnostics (the path as found, or the name given to `parse_str`).
    pub name: Arc<str>,
    /// Where it was read from, if from disk.
    pub path: Option<PathBuf>,
    /// The bytes, as lexed.
    pub bytes: Arc<[u8]>,
    line_starts: Vec<u32>,
    text: OnceLock<String>,
}

impl SourceFile {
    /// 0-based (line, column in characters) of a byte offset.
    #[must_use]
    pub fn line_col(&self, offset: u32) -> (usize, usize) {
        let line = match self.line_starts.binary_search(&offset) {
            Ok(l) => l,
            Err(l) => l.saturating_sub(1),
        };
        let start = self.line_starts.get(line).copied().unwrap_or(0) as usize;
        let end = (offset as usize).min(self.bytes.len()).max(start);
        // Characters, not bytes: UTF-8 continuation bytes do not start a character.
        let col = self.bytes[start..end].iter().filter(|&&b| (b & 0xc0) != 0x80).count();
        (line, col)
    }

    /// The text for display: the bytes, with each byte that is not valid UTF-8 shown as `?` so
    /// that byte offsets stay the same.
    #[must_use]
    pub fn text(&self) -> &str {
        self.text.get_or_init(|| display_text(&self.bytes))
    }

    /// Byte offsets at which each line starts.
    #[must_use]
    pub fn line_starts(&self) -> &[u32] {
        &self.line_starts
    }
}

fn display_text(bytes: &[u8]) -> String {
    let mut out = String::with_capacity(bytes.len());
    for chunk in bytes.utf8_chunks() {
        out.push_str(chunk.valid());
        out.extend(std::iter::repeat_n('?', chunk.invalid().len()));
    }
    out
}

/// All files read for one run of the reader.
#[derive(Clone, Debug, Default)]
pub struct SourceMap {
    files: Vec<SourceFile>,
}

impl SourceMap {
    /// An empty map.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a file and returns its id.
    pub fn add(&mut self, name: impl Into<Arc<str>>, path: Option<PathBuf>, bytes: impl Into<Arc<[u8]>>) -> FileId {
        let bytes = bytes.into();
        let mut line_starts = vec![0u32];
        for (i, &b) in bytes.iter().enumerate() {
            if b == b'\n' {
                line_starts.push(u32::try_from(i + 1).unwrap_or(u32::MAX));
            }
        }
        self.files.push(SourceFile { name: name.into(), path, bytes, line_starts, text: OnceLock::new() });
        FileId(u32::try_from(self.files.len() - 1).unwrap_or(u32::MAX))
    }

    /// The file with id `id`, if there is one.
    #[must_use]
    pub fn get(&self, id: FileId) -> Option<&SourceFile> {
        self.files.get(id.0 as usize)
    }

    /// All files in order of addition.
    #[must_use]
    pub fn files(&self) -> &[SourceFile] {
        &self.files
    }

    /// The location of bytes `start..end` of file `file`.
    #[must_use]
    pub fn loc(&self, file: FileId, start: u32, end: u32) -> Loc {
        match self.get(file) {
            Some(f) => {
                let (line, col) = f.line_col(start);
                Loc {
                    file,
                    name: f.name.clone(),
                    start,
                    end,
                    line: u32::try_from(line + 1).unwrap_or(u32::MAX),
                    col: u32::try_from(col + 1).unwrap_or(u32::MAX),
                }
            }
            None => Loc { file, name: Arc::from("<unknown>"), start, end, line: 1, col: 1 },
        }
    }
}
