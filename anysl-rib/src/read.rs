//! The reader: tokens → requests with arguments and parameter lists → builder calls.
//!
//! A request is its name followed by every value up to the next name. The values are gathered
//! first (so a malformed request is skipped as a whole and reading resumes at the next request
//! name), then matched against the request's argument shape (`args.rs`) from the table in `requests.rs`.
//! The reader itself handles `Declare`, `ReadArchive`, `ArchiveBegin`/`ArchiveEnd`,
//! `Option "searchpath"`, `version`, and checks that `…Begin`/`…End` pairs balance.

use crate::args::{declare, Args, Ctx, Diags, Val};
use crate::builder::BuildErrorKind;
use crate::diag::{codes, Diagnostic};
use crate::lex::{LexError, Lexer, Token, TokenKind};
use crate::param::ParamList;
use crate::requests::{dispatch, Dispatch, RibBuilder};
use crate::search::SearchPaths;
use crate::source::{FileId, Loc, SourceMap};
use crate::Options;
use std::collections::{HashMap, HashSet};
use std::io::Read as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Kinds of `…Begin`/`…End` blocks.
const BLOCKS: &[(&str, &str)] = &[
    ("FrameBegin", "FrameEnd"),
    ("WorldBegin", "WorldEnd"),
    ("AttributeBegin", "AttributeEnd"),
    ("TransformBegin", "TransformEnd"),
    ("SolidBegin", "SolidEnd"),
    ("ObjectBegin", "ObjectEnd"),
    ("MotionBegin", "MotionEnd"),
];

/// An inline archive: a byte range of a file, replayed by `ReadArchive`.
#[derive(Clone, Debug)]
struct InlineArchive {
    file: FileId,
    start: usize,
    end: usize,
}

/// What is being read: a file or an inline archive (for cycle detection).
#[derive(Clone, Debug, PartialEq, Eq)]
enum Source {
    File(PathBuf),
    Inline(String),
}

struct Frame {
    source: Source,
    /// The `ReadArchive` that started it (none for the top-level input).
    loc: Option<Loc>,
}

/// The result of reading: diagnostics, search paths, sources, counts.
pub(crate) struct Outcome {
    pub diagnostics: Vec<Diagnostic>,
    pub errors: usize,
    pub search_paths: SearchPaths,
    pub sources: SourceMap,
    pub requests: u64,
}

/// The reader's state for one run.
pub(crate) struct Reader<'a, B: RibBuilder + ?Sized> {
    builder: &'a mut B,
    options: &'a Options,
    ctx: Ctx,
    search: SearchPaths,
    blocks: Vec<(usize, Loc)>,
    archives: HashMap<String, InlineArchive>,
    stack: Vec<Frame>,
    file_cache: HashMap<PathBuf, FileId>,
    /// Index into the diagnostics of each unsupported request's warning, with its count.
    unsupported: HashMap<String, (usize, usize)>,
    unknown: HashSet<String>,
    requests: u64,
    stopped: bool,
}

impl<'a, B: RibBuilder + ?Sized> Reader<'a, B> {
    pub(crate) fn new(builder: &'a mut B, options: &'a Options) -> Self {
        Self {
            builder,
            options,
            ctx: Ctx {
                sources: SourceMap::new(),
                diags: Diags::default(),
                decls: HashMap::new(),
                undeclared: HashSet::new(),
            },
            search: options.search_paths.clone(),
            blocks: Vec::new(),
            archives: HashMap::new(),
            stack: Vec::new(),
            file_cache: HashMap::new(),
            unsupported: HashMap::new(),
            unknown: HashSet::new(),
            requests: 0,
            stopped: false,
        }
    }

    /// Reads a file from disk.
    pub(crate) fn read_path(mut self, path: &Path) -> Outcome {
        match load(path) {
            Ok(bytes) => {
                let file = self.ctx.sources.add(path.display().to_string(), Some(path.to_owned()), bytes);
                let key = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_owned());
                self.file_cache.insert(key.clone(), file);
                self.top(file, Source::File(key))
            }
            Err(e) => {
                let file = self.ctx.sources.add(path.display().to_string(), Some(path.to_owned()), Vec::new());
                let loc = self.ctx.loc(file, 0, 0);
                self.ctx.diags.push(Diagnostic::error(codes::IO, loc, format!("cannot read {}: {e}", path.display())));
                self.finish()
            }
        }
    }

    /// Reads bytes (gzip-compressed or not) named `name`.
    pub(crate) fn read_bytes(mut self, name: &str, bytes: &[u8]) -> Outcome {
        let data = match decompress(bytes) {
            Ok(d) => d,
            Err(e) => {
                let file = self.ctx.sources.add(name, None, Vec::new());
                let loc = self.ctx.loc(file, 0, 0);
                self.ctx.diags.push(Diagnostic::error(codes::IO, loc, format!("cannot decompress {name}: {e}")));
                return self.finish();
            }
        };
        let file = self.ctx.sources.add(name, None, data);
        self.top(file, Source::Inline(format!("<top>{name}")))
    }

    fn top(mut self, file: FileId, source: Source) -> Outcome {
        self.stack.push(Frame { source, loc: None });
        let len = self.ctx.sources.get(file).map_or(0, |f| f.bytes.len());
        self.run(file, 0, len);
        self.stack.pop();
        if !self.stopped {
            for (kind, loc) in std::mem::take(&mut self.blocks) {
                let (begin, end) = BLOCKS[kind];
                self.ctx.diags.push(
                    Diagnostic::error(codes::UNCLOSED_BLOCK, loc, format!("`{begin}` is never closed"))
                        .with_label("opened here")
                        .with_note(format!("add `{end}` after the last request of the block")),
                );
            }
        }
        self.finish()
    }

    fn finish(mut self) -> Outcome {
        for (name, (index, count)) in &self.unsupported {
            if *count > 1 {
                if let Some(d) = self.ctx.diags.items.get_mut(*index) {
                    d.notes.push(format!("`{name}` appears {count} times; only the first is shown"));
                }
            }
        }
        Outcome {
            errors: self.ctx.diags.errors,
            diagnostics: self.ctx.diags.items,
            search_paths: self.search,
            sources: self.ctx.sources,
            requests: self.requests,
        }
    }

    fn error(&mut self, d: Diagnostic) {
        self.ctx.diags.push(d);
        self.check_errors();
    }

    fn flush_lex(&mut self, file: FileId, errs: &mut Vec<LexError>) {
        for e in errs.drain(..) {
            let loc = self.ctx.loc(file, e.start, e.end);
            let mut d = Diagnostic::error(e.code, loc, e.message);
            if let Some(n) = e.note {
                d = d.with_note(n);
            }
            self.error(d);
        }
    }

    /// Reads the requests in bytes `start..end` of `file`.
    fn run(&mut self, file: FileId, start: usize, end: usize) {
        let Some(bytes) = self.ctx.sources.get(file).map(|f| Arc::clone(&f.bytes)) else { return };
        let mut lx = Lexer::range(&bytes, start, end);
        let mut errs = Vec::new();
        let mut peeked: Option<Token> = None;
        while !self.stopped {
            let tok = peeked.take().or_else(|| lx.next_token(&mut errs));
            self.flush_lex(file, &mut errs);
            let Some(tok) = tok else { break };
            match tok.kind {
                TokenKind::Name => {
                    let name = String::from_utf8_lossy(lx.text(&tok)).into_owned();
                    let (vals, poisoned) = self.gather(file, &mut lx, &mut errs, &mut peeked);
                    self.request(file, &name, &tok, vals, poisoned, &mut lx, &mut peeked);
                }
                TokenKind::Error => {}
                _ => {
                    let loc = self.ctx.loc(file, tok.start, tok.end);
                    let d = if tok.kind == TokenKind::Close {
                        Diagnostic::error(codes::UNMATCHED_BRACKET, loc, "`]` without `[`").with_label("unmatched `]`")
                    } else {
                        Diagnostic::error(codes::EXPECTED_REQUEST, loc, "expected a request name")
                            .with_label("this value belongs to no request")
                    };
                    self.error(d);
                    // Skip to the next request name.
                    loop {
                        let t = lx.next_token(&mut errs);
                        self.flush_lex(file, &mut errs);
                        match t {
                            Some(t) if t.kind == TokenKind::Name => {
                                peeked = Some(t);
                                break;
                            }
                            Some(_) => {}
                            None => break,
                        }
                    }
                }
            }
        }
    }

    /// Gathers the values after a request name, up to the next name. Returns them and whether
    /// the request is malformed (already reported).
    fn gather(
        &mut self,
        file: FileId,
        lx: &mut Lexer<'_>,
        errs: &mut Vec<LexError>,
        peeked: &mut Option<Token>,
    ) -> (Vec<Val>, bool) {
        let mut vals = Vec::new();
        let mut poisoned = false;
        loop {
            let t = lx.next_token(errs);
            self.flush_lex(file, errs);
            let Some(t) = t else { break };
            match t.kind {
                TokenKind::Name => {
                    *peeked = Some(t);
                    break;
                }
                TokenKind::Number { value, .. } => vals.push(Val::Num { v: value, start: t.start, end: t.end }),
                TokenKind::Str(s) => vals.push(Val::Str { s, start: t.start, end: t.end }),
                TokenKind::Error => poisoned = true,
                TokenKind::Close => {
                    let loc = self.ctx.loc(file, t.start, t.end);
                    self.error(
                        Diagnostic::error(codes::UNMATCHED_BRACKET, loc, "`]` without `[`").with_label("unmatched `]`"),
                    );
                    poisoned = true;
                }
                TokenKind::Open => match self.array(file, t.start, lx, errs, peeked) {
                    Some(v) => vals.push(v),
                    None => {
                        poisoned = true;
                        if peeked.is_some() {
                            break;
                        }
                    }
                },
            }
        }
        (vals, poisoned)
    }

    /// Reads an array after its `[`. `None` when malformed (reported); a request name that ends
    /// an unclosed array is left in `peeked`.
    fn array(
        &mut self,
        file: FileId,
        open: u32,
        lx: &mut Lexer<'_>,
        errs: &mut Vec<LexError>,
        peeked: &mut Option<Token>,
    ) -> Option<Val> {
        let mut nums = Vec::new();
        let mut strs = Vec::new();
        let mut bad = false;
        loop {
            let t = lx.next_token(errs);
            self.flush_lex(file, errs);
            let Some(t) = t else {
                self.unclosed(file, open);
                return None;
            };
            match t.kind {
                TokenKind::Close => {
                    if bad {
                        return None;
                    }
                    return Some(if strs.is_empty() {
                        Val::Nums { v: nums, start: open, end: t.end }
                    } else {
                        Val::Strs { v: strs, start: open, end: t.end }
                    });
                }
                TokenKind::Number { value, .. } => {
                    if !strs.is_empty() && !bad {
                        self.mixed(file, open, t.start, t.end);
                        bad = true;
                    }
                    nums.push(value);
                }
                TokenKind::Str(s) => {
                    if !nums.is_empty() && !bad {
                        self.mixed(file, open, t.start, t.end);
                        bad = true;
                    }
                    strs.push(s);
                }
                TokenKind::Open => {
                    if !bad {
                        let loc = self.ctx.loc(file, t.start, t.end);
                        self.error(
                            Diagnostic::error(codes::BAD_ARRAY, loc, "arrays cannot be nested")
                                .with_label("`[` inside an array"),
                        );
                        bad = true;
                    }
                }
                TokenKind::Error => bad = true,
                TokenKind::Name => {
                    self.unclosed(file, open);
                    *peeked = Some(t);
                    return None;
                }
            }
        }
    }

    fn unclosed(&mut self, file: FileId, open: u32) {
        let loc = self.ctx.loc(file, open, open + 1);
        self.error(
            Diagnostic::error(codes::UNCLOSED_ARRAY, loc, "`[` without `]`")
                .with_label("this array is not closed")
                .with_note("close the array with `]` before the next request"),
        );
    }

    fn mixed(&mut self, file: FileId, open: u32, start: u32, end: u32) {
        let loc = self.ctx.loc(file, start, end);
        let open_loc = self.ctx.loc(file, open, open + 1);
        self.error(
            Diagnostic::error(codes::BAD_ARRAY, loc, "numbers and strings mixed in one array")
                .with_label("differs from the first element")
                .with_secondary(open_loc, "array starts here"),
        );
    }

    #[allow(clippy::too_many_arguments)]
    fn request(
        &mut self,
        file: FileId,
        name: &str,
        tok: &Token,
        vals: Vec<Val>,
        poisoned: bool,
        lx: &mut Lexer<'_>,
        peeked: &mut Option<Token>,
    ) {
        self.requests += 1;
        let loc = self.ctx.loc(file, tok.start, tok.end);
        if self.requests > self.options.max_requests {
            self.error(Diagnostic::error(
                codes::LIMIT,
                loc,
                format!("more than {} requests; reading stops here", self.options.max_requests),
            ));
            self.stopped = true;
            return;
        }
        match name {
            "version" => return,
            "ArchiveBegin" => {
                self.archive_begin(file, name, &loc, vals, poisoned, lx, peeked);
                return;
            }
            "ArchiveEnd" => {
                self.error(
                    Diagnostic::error(codes::UNBALANCED_END, loc, "`ArchiveEnd` without `ArchiveBegin`")
                        .with_label("no archive is open"),
                );
                return;
            }
            _ => {}
        }
        // Blocks balance even when the request itself is malformed.
        if let Some(kind) = BLOCKS.iter().position(|(b, _)| *b == name) {
            self.blocks.push((kind, loc.clone()));
        } else if let Some(kind) = BLOCKS.iter().position(|(_, e)| *e == name) {
            let open = self.blocks.iter().rposition(|(k, _)| *k == kind);
            match (open, self.blocks.last()) {
                (Some(i), _) if i + 1 == self.blocks.len() => {
                    self.blocks.pop();
                }
                (Some(i), Some((k, inner))) => {
                    // Blocks opened inside the matching one were not closed: report the
                    // innermost and close them all.
                    let (inner, other, other_end) = (inner.clone(), BLOCKS[*k].0, BLOCKS[*k].1);
                    self.blocks.truncate(i);
                    self.error(
                        Diagnostic::error(
                            codes::UNBALANCED_END,
                            loc,
                            format!("`{name}` does not match the open `{other}`"),
                        )
                        .with_label(format!("expected `{other_end}`"))
                        .with_secondary(inner, format!("`{other}` opened here")),
                    );
                    return;
                }
                _ => {
                    let begin = BLOCKS[kind].0;
                    self.error(
                        Diagnostic::error(codes::UNBALANCED_END, loc, format!("`{name}` without `{begin}`"))
                            .with_label(format!("no `{begin}` is open")),
                    );
                    return;
                }
            }
        }
        if poisoned {
            return;
        }
        let mut args = Args {
            usage: "",
            request: name,
            file,
            name_start: tok.start,
            name_end: tok.end,
            vals,
            pos: 0,
            ctx: &mut self.ctx,
        };
        match name {
            "Declare" => {
                declare(&mut args);
                return;
            }
            "ReadArchive" => {
                args.usage = "ReadArchive filename";
                let archive = args.string("filename");
                let done = args.finish();
                let at = args.vals.first().map_or((tok.start, tok.end), Val::span);
                if let (Ok(archive), Ok(())) = (archive, done) {
                    let at = self.ctx.loc(file, at.0, at.1);
                    self.read_archive(file, &archive, at);
                }
                self.check_errors();
                return;
            }
            "Option" if matches!(args.vals.first(), Some(Val::Str { s, .. }) if s == "searchpath") => {
                args.usage = "Option \"searchpath\" kind paths";
                let params = args.string("name").and_then(|_| args.params("params"));
                if let Ok(params) = params {
                    self.search_path(&params, &loc);
                }
                self.check_errors();
                return;
            }
            _ => {}
        }
        let result = dispatch(&mut *self.builder, name, &loc, &mut args);
        self.check_errors();
        match result {
            Dispatch::Bad => {}
            Dispatch::Unknown => {
                if self.unknown.insert(name.to_owned()) {
                    self.ctx.diags.push(
                        Diagnostic::warning(codes::UNKNOWN_REQUEST, loc, format!("unknown request `{name}`"))
                            .with_label("skipped with its arguments"),
                    );
                }
            }
            Dispatch::Built(Ok(())) => {}
            Dispatch::Built(Err(e)) => self.build_error(name, loc, e),
        }
    }

    fn check_errors(&mut self) {
        if self.ctx.diags.errors >= self.options.max_errors && !self.stopped {
            self.stopped = true;
            let loc = d_loc(&self.ctx.diags.items);
            self.ctx.diags.items.push(Diagnostic::error(
                codes::LIMIT,
                loc,
                format!("too many errors ({}); reading stops here", self.options.max_errors),
            ));
        }
    }

    fn build_error(&mut self, name: &str, loc: Loc, e: crate::BuildError) {
        match e.kind {
            BuildErrorKind::Unsupported => {
                if let Some((_, count)) = self.unsupported.get_mut(name) {
                    *count += 1;
                } else {
                    let index = self.ctx.diags.items.len();
                    self.ctx.diags.push(
                        Diagnostic::warning(
                            codes::UNSUPPORTED_REQUEST,
                            loc,
                            format!("unsupported request `{name}` (ignored)"),
                        )
                        .with_label("not supported by this builder"),
                    );
                    self.unsupported.insert(name.to_owned(), (index, 1));
                }
            }
            BuildErrorKind::Warning | BuildErrorKind::Error => {
                let mut d = if e.kind == BuildErrorKind::Error {
                    Diagnostic::error(codes::BUILD, loc, e.message)
                } else {
                    Diagnostic::warning(codes::BUILD_WARNING, loc, e.message)
                };
                d.label = format!("in `{name}`");
                d.notes = e.notes;
                self.error(d);
            }
        }
    }

    fn search_path(&mut self, params: &ParamList, loc: &Loc) {
        for p in params {
            let value = p.strings().map(|v| v.join(":")).unwrap_or_default();
            let paths = self.search.expand(&p.name, &value, &self.options.search_paths);
            self.search.set(p.name.clone(), paths.clone());
            if let Err(e) = self.builder.search_path(loc, &p.name, &paths) {
                if e.kind != BuildErrorKind::Unsupported {
                    self.build_error("Option", loc.clone(), e);
                }
            }
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn archive_begin(
        &mut self,
        file: FileId,
        name: &str,
        loc: &Loc,
        vals: Vec<Val>,
        poisoned: bool,
        lx: &mut Lexer<'_>,
        peeked: &mut Option<Token>,
    ) {
        let body_start = peeked.as_ref().map_or(lx.pos(), |t| t.start as usize);
        let mut args = Args {
            usage: "ArchiveBegin name params",
            request: name,
            file,
            name_start: loc.start,
            name_end: loc.end,
            vals,
            pos: 0,
            ctx: &mut self.ctx,
        };
        let archive = if poisoned { None } else { args.string("name").ok() };
        if archive.is_some() {
            // ArchiveBegin's parameters are not used; a malformed list is still reported.
            let _ = args.params("params");
        }
        // Skip to the matching ArchiveEnd.
        let mut errs = Vec::new();
        let mut depth = 1usize;
        let mut body_end = None;
        loop {
            let t = peeked.take().or_else(|| lx.next_token(&mut errs));
            self.flush_lex(file, &mut errs);
            let Some(t) = t else { break };
            if t.kind == TokenKind::Name {
                match lx.text(&t) {
                    b"ArchiveBegin" => depth += 1,
                    b"ArchiveEnd" => {
                        depth -= 1;
                        if depth == 0 {
                            body_end = Some(t.start as usize);
                            // Drop ArchiveEnd's arguments (there are none by the spec).
                            break;
                        }
                    }
                    _ => {}
                }
            }
        }
        match body_end {
            Some(end) => {
                if let Some(a) = archive {
                    self.archives.insert(a, InlineArchive { file, start: body_start, end });
                }
            }
            None => self.error(
                Diagnostic::error(codes::UNCLOSED_ARCHIVE, loc.clone(), "`ArchiveBegin` without `ArchiveEnd`")
                    .with_label("archive opened here")
                    .with_note("add `ArchiveEnd` after the archive's last request"),
            ),
        }
    }

    fn read_archive(&mut self, file: FileId, name: &str, at: Loc) {
        if self.stack.len() > self.options.max_archive_depth {
            self.error(
                Diagnostic::error(
                    codes::ARCHIVE_DEPTH,
                    at,
                    format!("archives nested more than {} deep", self.options.max_archive_depth),
                )
                .with_label("reading stops here"),
            );
            return;
        }
        if let Some(a) = self.archives.get(name).cloned() {
            let source = Source::Inline(name.to_owned());
            if self.cycle(&source, name, &at) {
                return;
            }
            self.stack.push(Frame { source, loc: Some(at) });
            self.run(a.file, a.start, a.end);
            self.stack.pop();
            return;
        }
        let dir = self.ctx.sources.get(file).and_then(|f| f.path.as_ref()).and_then(|p| p.parent()).map(Path::to_owned);
        let mut candidates = Vec::new();
        let path = Path::new(name);
        if path.is_absolute() {
            candidates.push(path.to_owned());
        } else {
            match &dir {
                Some(d) => candidates.push(d.join(path)),
                None => candidates.push(path.to_owned()),
            }
            for p in self.search.get("archive") {
                candidates.push(p.join(path));
            }
        }
        let Some(found) = candidates.iter().find(|c| c.is_file()).cloned() else {
            let mut d = Diagnostic::error(codes::ARCHIVE_NOT_FOUND, at, format!("archive \"{name}\" not found"))
                .with_label("no such file or inline archive");
            let tried: Vec<String> = candidates.iter().map(|c| c.display().to_string()).collect();
            d = d.with_note(format!("looked in: {}", tried.join(", ")));
            d = d.with_note("set the archive search path with `Option \"searchpath\" \"archive\" [\"dir:@\"]`");
            self.error(d);
            return;
        };
        let key = std::fs::canonicalize(&found).unwrap_or_else(|_| found.clone());
        let source = Source::File(key.clone());
        if self.cycle(&source, name, &at) {
            return;
        }
        let id = match self.file_cache.get(&key) {
            Some(&id) => id,
            None => match load(&found) {
                Ok(bytes) => {
                    let id = self.ctx.sources.add(found.display().to_string(), Some(found.clone()), bytes);
                    self.file_cache.insert(key, id);
                    id
                }
                Err(e) => {
                    self.error(
                        Diagnostic::error(codes::IO, at, format!("cannot read {}: {e}", found.display()))
                            .with_label("read here"),
                    );
                    return;
                }
            },
        };
        self.stack.push(Frame { source, loc: Some(at) });
        let len = self.ctx.sources.get(id).map_or(0, |f| f.bytes.len());
        self.run(id, 0, len);
        self.stack.pop();
    }

    /// Reports and returns true when `source` is already being read.
    fn cycle(&mut self, source: &Source, name: &str, at: &Loc) -> bool {
        let Some(i) = self.stack.iter().position(|f| &f.source == source) else { return false };
        let mut d = Diagnostic::error(codes::INCLUDE_CYCLE, at.clone(), format!("archive \"{name}\" reads itself"))
            .with_label("read again here");
        for f in &self.stack[i + 1..] {
            if let Some(l) = &f.loc {
                d = d.with_secondary(l.clone(), "read from here");
            }
        }
        d = d.with_note("an archive may not (indirectly) read itself");
        self.error(d);
        true
    }
}

fn d_loc(items: &[Diagnostic]) -> Loc {
    items.last().map(|d| d.loc.clone()).unwrap_or_else(|| SourceMap::new().loc(FileId(0), 0, 0))
}

/// Reads a file, decompressing it when it is gzip-compressed.
fn load(path: &Path) -> std::io::Result<Vec<u8>> {
    decompress(&std::fs::read(path)?)
}

/// Decompresses gzip data (detected by its magic bytes `1f 8b`); other data is returned as is.
fn decompress(bytes: &[u8]) -> std::io::Result<Vec<u8>> {
    let data = if bytes.starts_with(&[0x1f, 0x8b]) {
        let mut out = Vec::new();
        flate2::read::MultiGzDecoder::new(bytes).read_to_end(&mut out)?;
        out
    } else {
        bytes.to_vec()
    };
    if u32::try_from(data.len()).is_err() {
        return Err(std::io::Error::other("file larger than 4 GiB"));
    }
    Ok(data)
}
