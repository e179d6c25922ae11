//! The preprocessor: a C-like preprocessor working on [`Token`]s.
//!
//! Supported: `#include "file"` and `#include <file>`, `#define` (object-like and
//! function-like, with `#` stringification and `##` pasting), `#undef`, `#if`, `#ifdef`,
//! `#ifndef`, `#elif`, `#else`, `#endif`, `#error`; `#pragma` and `#line` are accepted and
//! ignored (spans already name the real file and line of every token, so `#line` has nothing
//! to fix up). An empty `#` line is allowed, as in C.
//!
//! * **Include search**: for both forms, the directory of the including file first, then the
//!   `-I` directories in order ([`PpOptions::include_dirs`]). Each included file becomes its
//!   own [`FileId`] in the [`SourceMap`], so diagnostics name that file and its lines.
//!   Nesting deeper than [`MAX_INCLUDE_DEPTH`] is reported as [`codes::INCLUDE_DEPTH`]
//!   (usually a recursive include without a guard) and stops further includes.
//! * **Macros**: expansion follows the C rules in the "hide set" formulation: a token made by
//!   expanding macro `M` is never expanded as `M` again, so self-referential macros terminate.
//!   Arguments are fully expanded before substitution (except next to `#`/`##`) and the result
//!   is rescanned. Tokens made by an expansion carry the span of the macro use, so carets point
//!   at the use; tokens from arguments keep their own spans.
//! * **Predefined macros**: none, apart from the `-D` ones ([`PpOptions::defines`]; a define
//!   without a value is `1`, as with C compilers).
//! * **Budgets**: the total work (tokens scanned during expansion) and the nesting of macro
//!   arguments are bounded, so pathological input ends in a diagnostic, not a hang or a stack
//!   overflow.
//!
//! Files are read through a [`SourceLoader`], so tests can serve includes from memory.

use super::lex::{lex, Punct, Token, TokenKind};
use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::span::{FileId, SourceMap, Span};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// Preprocessor settings (what `-I` and `-D` give on a command line).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PpOptions {
    /// `-I` directories, searched in order after the including file's own directory.
    pub include_dirs: Vec<PathBuf>,
    /// `-D NAME[=VALUE]`: `(name, value)`; no value defines `NAME` as `1`.
    pub defines: Vec<(String, Option<String>)>,
}

/// Reads source files for `#include` (and the main file for [`super::parse_file`]).
pub trait SourceLoader {
    /// The text of the file at `path`, or an error message such as "No such file".
    fn load(&mut self, path: &Path) -> Result<String, String>;
}

/// Reads files from disk.
#[derive(Clone, Copy, Debug, Default)]
pub struct FsLoader;

impl SourceLoader for FsLoader {
    fn load(&mut self, path: &Path) -> Result<String, String> {
        // Only regular files: `/dev/zero` or a FIFO would never end.
        match std::fs::metadata(path) {
            Ok(m) if m.is_file() => {}
            Ok(_) => return Err("not a regular file".into()),
            Err(e) => return Err(e.to_string()),
        }
        std::fs::read(path).map(|b| String::from_utf8_lossy(&b).into_owned()).map_err(|e| e.to_string())
    }
}

/// Any `FnMut(&Path) -> Option<String>` serves files (handy for in-memory tests).
impl<F: FnMut(&Path) -> Option<String>> SourceLoader for F {
    fn load(&mut self, path: &Path) -> Result<String, String> {
        self(path).ok_or_else(|| "no such file".to_owned())
    }
}

/// Deepest `#include` nesting accepted.
pub const MAX_INCLUDE_DEPTH: usize = 40;
/// Deepest nesting of macro calls inside macro arguments.
pub const MAX_MACRO_NESTING: usize = 200;
/// Most tokens scanned during macro expansion in one run (guards against exponential macros).
pub const MAX_EXPANSION_WORK: usize = 4_000_000;
/// Most `#include`s processed in one run.
pub const MAX_INCLUDES: usize = 10_000;
/// Most tokens in the preprocessed output.
pub const MAX_OUTPUT_TOKENS: usize = 4_000_000;

/// Preprocesses file `main` (already in `sources`) and returns the token stream, ending with
/// one [`TokenKind::Eof`] token.
pub fn preprocess(
    sources: &mut SourceMap,
    main: FileId,
    opts: &PpOptions,
    loader: &mut dyn SourceLoader,
    diags: &mut Diagnostics,
) -> Vec<Token> {
    let mut pp = Pp {
        sources,
        opts,
        loader,
        diags,
        macros: HashMap::new(),
        next_macro_id: 0,
        out: Vec::new(),
        work: 0,
        aborted: false,
        includes_disabled: false,
        file_cache: HashMap::new(),
        include_count: 0,
    };
    if !opts.defines.is_empty() {
        let mut text = String::new();
        for (name, value) in &opts.defines {
            let value = value.as_deref().unwrap_or("1").replace('\n', " ");
            text.push_str(&format!("#define {name} {value}\n"));
        }
        let id = pp.sources.add("<command line>", None, text);
        pp.run_file(id, 0);
    }
    pp.run_file(main, 0);
    let len = u32::try_from(pp.sources.get(main).text.len()).unwrap_or(u32::MAX);
    let mut out = pp.out;
    out.push(Token { kind: TokenKind::Eof, span: Span::new(main, len, len), line_start: true, space_before: true });
    out
}

/// Ids of the macros a token must not be expanded as.
type HideSet = Rc<Vec<u32>>;

#[derive(Clone, Debug)]
struct PTok {
    tok: Token,
    hide: HideSet,
}

#[derive(Clone, Debug)]
struct Macro {
    id: u32,
    /// `Some` for function-like macros.
    params: Option<Vec<String>>,
    /// The last parameter is `...` (named `__VA_ARGS__`): it takes the remaining arguments,
    /// commas included.
    variadic: bool,
    body: Vec<Token>,
}

struct Cond {
    /// The current branch is being emitted.
    active: bool,
    /// Some branch of this `#if` chain was taken (or the parent is inactive).
    done: bool,
    /// `#else` seen.
    seen_else: bool,
    /// The `#if` (for "unterminated" errors).
    span: Span,
}

struct Pp<'a> {
    sources: &'a mut SourceMap,
    opts: &'a PpOptions,
    loader: &'a mut dyn SourceLoader,
    diags: &'a mut Diagnostics,
    macros: HashMap<String, Macro>,
    next_macro_id: u32,
    out: Vec<Token>,
    work: usize,
    /// A budget ran out: stop producing tokens (one diagnostic was reported).
    aborted: bool,
    /// An include went too deep: no more includes (avoids 2^depth blow-ups).
    includes_disabled: bool,
    file_cache: HashMap<PathBuf, FileId>,
    include_count: usize,
}

/// Lexer diagnostics of one file, released as the preprocessor passes their position (dropped
/// inside skipped `#if` regions).
struct LexDiags {
    items: Vec<Diagnostic>,
    next: usize,
}

impl LexDiags {
    /// Reports (if `keep`) or drops every lexer diagnostic starting before `pos`.
    fn flush(&mut self, pos: u32, keep: bool, diags: &mut Diagnostics) {
        while let Some(d) = self.items.get(self.next) {
            if d.span.start >= pos {
                break;
            }
            if keep {
                diags.push(d.clone());
            }
            self.next += 1;
        }
    }
}

impl Pp<'_> {
    fn error(&mut self, code: &'static str, span: Span, msg: impl Into<String>) -> &mut Diagnostic {
        self.diags.push(Diagnostic::error(code, span, msg));
        let n = self.diags.items.len() - 1;
        &mut self.diags.items[n]
    }

    fn abort(&mut self, span: Span, what: &str) {
        if !self.aborted {
            self.aborted = true;
            self.error(codes::PP_ERROR, span, format!("preprocessing stopped: {what}")).notes.push(
                "this usually comes from a macro that expands to ever more copies of itself, or from a recursive \
                 #include"
                    .into(),
            );
        }
    }

    fn run_file(&mut self, file: FileId, depth: usize) {
        let (toks, lex_diags) = lex(&self.sources.get(file).text, file);
        let mut lexd = LexDiags { items: lex_diags, next: 0 };
        let mut conds: Vec<Cond> = Vec::new();
        let mut i = 0;
        while i < toks.len() && !self.aborted {
            let active = conds.last().is_none_or(|c| c.active);
            let t = &toks[i];
            if t.is(Punct::Hash) && t.line_start {
                let mut j = i + 1;
                while j < toks.len() && !toks[j].line_start {
                    j += 1;
                }
                let line = &toks[i + 1..j];
                let end = toks.get(j).map_or(u32::MAX, |t| t.span.start);
                // Lexical errors in directive lines of skipped regions, and in the free text of
                // `#error`/`#pragma`, are not errors.
                let name = line.first().and_then(Token::word).unwrap_or("");
                let keep = active && !matches!(name, "error" | "pragma" | "line" | "warning" | "ident" | "sccs");
                lexd.flush(end, keep, self.diags);
                self.directive(t.span, line, &mut conds, file, depth);
                i = j;
                continue;
            }
            // A run of ordinary tokens up to the next directive.
            let mut j = i;
            while j < toks.len() && !(toks[j].is(Punct::Hash) && toks[j].line_start) {
                j += 1;
            }
            let end = toks.get(j).map_or(u32::MAX, |t| t.span.start);
            lexd.flush(end, active, self.diags);
            if active {
                let empty: HideSet = Rc::new(Vec::new());
                let run: Vec<PTok> = toks[i..j].iter().map(|t| PTok { tok: t.clone(), hide: empty.clone() }).collect();
                let expanded = self.expand(run, 0);
                for p in expanded {
                    if self.out.len() >= MAX_OUTPUT_TOKENS {
                        self.abort(p.tok.span, "too many tokens");
                        break;
                    }
                    self.out.push(p.tok);
                }
            }
            i = j;
        }
        let keep = conds.last().is_none_or(|c| c.active);
        lexd.flush(u32::MAX, keep, self.diags);
        if let Some(c) = conds.first() {
            let span = c.span;
            self.error(codes::UNBALANCED_CONDITIONAL, span, "`#if` without `#endif`")
                .with_label_mut("this conditional is not closed before the end of the file");
        }
    }

    fn directive(&mut self, hash: Span, line: &[Token], conds: &mut Vec<Cond>, file: FileId, depth: usize) {
        let active = conds.last().is_none_or(|c| c.active);
        let Some(name_tok) = line.first() else { return }; // `#` alone: null directive
        let span = hash.to(name_tok.span);
        let args = &line[1..];
        let name = name_tok.word().unwrap_or("");
        match name {
            "if" | "ifdef" | "ifndef" => {
                if !active {
                    conds.push(Cond { active: false, done: true, seen_else: false, span });
                    return;
                }
                let v = match name {
                    "if" => self.eval_condition(span, args),
                    _ => {
                        let defined = match args.first().and_then(Token::word) {
                            Some(n) => self.macros.contains_key(n),
                            None => {
                                self.error(codes::BAD_DIRECTIVE, span, format!("`#{name}` needs a macro name"));
                                false
                            }
                        };
                        defined == (name == "ifdef")
                    }
                };
                conds.push(Cond { active: v, done: v, seen_else: false, span });
            }
            "elif" | "else" => {
                let Some(c) = conds.last() else {
                    self.error(codes::UNBALANCED_CONDITIONAL, span, format!("`#{name}` without `#if`"));
                    return;
                };
                if c.seen_else {
                    let prev = c.span;
                    self.error(codes::UNBALANCED_CONDITIONAL, span, format!("`#{name}` after `#else`"))
                        .secondary
                        .push((prev, "in this conditional".into()));
                    return;
                }
                let done = c.done;
                let take = if done {
                    false
                } else if name == "elif" {
                    self.eval_condition(span, args)
                } else {
                    true
                };
                if let Some(c) = conds.last_mut() {
                    c.active = take;
                    c.done = done || take;
                    c.seen_else = name == "else";
                }
            }
            "endif" => {
                if conds.pop().is_none() {
                    self.error(codes::UNBALANCED_CONDITIONAL, span, "`#endif` without `#if`");
                }
            }
            _ if !active => {}
            "define" => self.define(span, args),
            "undef" => match args.first().and_then(Token::word) {
                Some(n) => {
                    self.macros.remove(n);
                }
                None => {
                    self.error(codes::BAD_DIRECTIVE, span, "`#undef` needs a macro name");
                }
            },
            "include" => self.include(span, args, file, depth),
            "error" => {
                let text = self.rest_of_line(args);
                let msg = if text.is_empty() { "#error".to_owned() } else { text };
                self.error(codes::PP_ERROR, span, msg);
            }
            // GNU cpp's `#ident "…"` / `#sccs "…"` (version strings in old shader sources).
            "pragma" | "line" | "ident" | "sccs" => {}
            "warning" => {
                let text = self.rest_of_line(args);
                let msg = if text.is_empty() { "#warning".to_owned() } else { text };
                self.diags.push(Diagnostic::warning(codes::PP_WARNING, span, msg).with_label("#warning"));
            }
            _ => {
                // `# 12 "file"` (line markers) are ignored like `#line`.
                if !matches!(name_tok.kind, TokenKind::Number(_)) {
                    let what = self.sources.snippet(name_tok.span).to_owned();
                    self.error(codes::BAD_DIRECTIVE, span, format!("unknown preprocessor directive `#{what}`"))
                        .notes
                        .push("known directives: include, define, undef, if, ifdef, ifndef, elif, else, endif, error, warning, pragma, line, ident".into());
                }
            }
        }
    }

    /// The source text of a directive's arguments (for `#error`).
    fn rest_of_line(&self, args: &[Token]) -> String {
        match (args.first(), args.last()) {
            (Some(a), Some(b)) if a.span.file == b.span.file => {
                self.sources.snippet(Span::new(a.span.file, a.span.start, b.span.end)).to_owned()
            }
            _ => String::new(),
        }
    }

    fn define(&mut self, span: Span, args: &[Token]) {
        let Some(name_tok) = args.first() else {
            self.error(codes::BAD_DIRECTIVE, span, "`#define` needs a macro name");
            return;
        };
        let Some(name) = name_tok.word() else {
            self.error(codes::BAD_DIRECTIVE, name_tok.span, format!("expected a macro name, found {}", name_tok.kind));
            return;
        };
        let name = name.to_owned();
        let mut rest = &args[1..];
        let mut params = None;
        let mut variadic = false;
        if let Some(lp) = rest.first().filter(|t| t.is(Punct::LParen) && !t.space_before) {
            let mut ps = Vec::new();
            let mut k = 1;
            let mut ok = false;
            // `()` or `(a)` or `(a, b, …)`
            if rest.get(1).is_some_and(|t| t.is(Punct::RParen)) {
                ok = true;
                k = 2;
            } else {
                while let Some(t) = rest.get(k) {
                    // `...` (C99): the remaining arguments, as `__VA_ARGS__`.
                    if t.is(Punct::Dot)
                        && rest.get(k + 1).is_some_and(|d| d.is(Punct::Dot))
                        && rest.get(k + 2).is_some_and(|d| d.is(Punct::Dot))
                        && rest.get(k + 3).is_some_and(|r| r.is(Punct::RParen))
                    {
                        ps.push("__VA_ARGS__".to_owned());
                        variadic = true;
                        ok = true;
                        k += 4;
                        break;
                    }
                    let Some(p) = t.word() else { break };
                    ps.push(p.to_owned());
                    match rest.get(k + 1) {
                        Some(t) if t.is(Punct::Comma) => k += 2,
                        Some(t) if t.is(Punct::RParen) => {
                            ok = true;
                            k += 2;
                            break;
                        }
                        _ => break,
                    }
                }
            }
            if !ok {
                let at = rest.get(k).map_or(lp.span, |t| t.span);
                self.error(codes::BAD_DIRECTIVE, at, "malformed macro parameter list")
                    .notes
                    .push("write `#define NAME(a, b) replacement`".into());
                return;
            }
            params = Some(ps);
            rest = &rest[k..];
        }
        let id = self.next_macro_id;
        self.next_macro_id = self.next_macro_id.wrapping_add(1);
        self.macros.insert(name, Macro { id, params, variadic, body: rest.to_vec() });
    }

    fn include(&mut self, span: Span, args: &[Token], file: FileId, depth: usize) {
        // The name: a string literal, or the raw text between `<` and `>`; macros are expanded
        // first if neither form is written directly.
        let expanded;
        let args = if matches!(args.first().map(|t| &t.kind), Some(TokenKind::Str(_)))
            || args.first().is_some_and(|t| t.is(Punct::Lt))
        {
            args
        } else {
            let empty: HideSet = Rc::new(Vec::new());
            let run = args.iter().map(|t| PTok { tok: t.clone(), hide: empty.clone() }).collect();
            expanded = self.expand(run, 0).into_iter().map(|p| p.tok).collect::<Vec<_>>();
            &expanded[..]
        };
        let name = match args.first().map(|t| &t.kind) {
            Some(TokenKind::Str(s)) => s.clone(),
            Some(TokenKind::Punct(Punct::Lt)) => {
                let close = args.iter().position(|t| t.is(Punct::Gt));
                match close {
                    Some(c) if c > 1 && args[1].span.file == args[c - 1].span.file => self
                        .sources
                        .snippet(Span::new(args[1].span.file, args[1].span.start, args[c - 1].span.end))
                        .to_owned(),
                    _ => {
                        self.error(codes::BAD_DIRECTIVE, span, "malformed `#include <…>`");
                        return;
                    }
                }
            }
            _ => {
                self.error(codes::BAD_DIRECTIVE, span, "`#include` expects \"file\" or <file>");
                return;
            }
        };
        // The caret goes under the file name (`"x.h"` or `<x.h>`).
        let name_span = match args.first() {
            Some(t) if t.is(Punct::Lt) => args.iter().find(|t| t.is(Punct::Gt)).map_or(t.span, |gt| t.span.to(gt.span)),
            Some(t) => t.span,
            None => span,
        };
        if self.includes_disabled {
            return;
        }
        self.include_count += 1;
        if self.include_count > MAX_INCLUDES {
            self.abort(name_span, "too many #includes");
            return;
        }
        if depth + 1 > MAX_INCLUDE_DEPTH {
            self.includes_disabled = true;
            self.error(
                codes::INCLUDE_DEPTH,
                name_span,
                format!("`#include` nested more than {MAX_INCLUDE_DEPTH} deep"),
            )
            .notes
            .push("is this file including itself? Guard it with `#ifndef NAME` / `#define NAME` / `#endif`".into());
            return;
        }
        // Search order: the including file's directory, then the -I directories.
        let src = self.sources.get(file);
        let own_dir = src.path.clone().unwrap_or_else(|| PathBuf::from(&src.name)).parent().map(Path::to_path_buf);
        let mut candidates = Vec::new();
        let rel = Path::new(&name);
        if rel.is_absolute() {
            candidates.push(rel.to_path_buf());
        } else {
            candidates.extend(own_dir.iter().map(|d| d.join(rel)));
            candidates.extend(self.opts.include_dirs.iter().map(|d| d.join(rel)));
        }
        for path in &candidates {
            if let Some(&id) = self.file_cache.get(path) {
                self.run_file(id, depth + 1);
                return;
            }
            if let Ok(text) = self.loader.load(path) {
                let id = self.sources.add(path.to_string_lossy().into_owned(), Some(path.clone()), text);
                self.file_cache.insert(path.clone(), id);
                self.run_file(id, depth + 1);
                return;
            }
        }
        let searched: Vec<String> = candidates.iter().map(|p| p.display().to_string()).collect();
        let d = self.error(codes::INCLUDE_NOT_FOUND, name_span, format!("cannot find include file `{name}`"));
        d.notes.push(format!("searched: {}", searched.join(", ")));
        d.notes.push("add the directory with `-I DIR`".into());
    }

    // ---- macro expansion ------------------------------------------------------------------

    /// Fully expands `input`.
    fn expand(&mut self, input: Vec<PTok>, nesting: usize) -> Vec<PTok> {
        let mut stack: Vec<PTok> = input;
        stack.reverse();
        let mut out = Vec::new();
        while let Some(t) = stack.pop() {
            self.work += 1;
            if self.work > MAX_EXPANSION_WORK || stack.len() > MAX_OUTPUT_TOKENS {
                self.abort(t.tok.span, "macro expansion too large");
            }
            if self.aborted {
                break;
            }
            let mac = match t.tok.word().and_then(|w| self.macros.get(w)) {
                Some(m) if !t.hide.contains(&m.id) => m.clone(),
                _ => {
                    out.push(t);
                    continue;
                }
            };
            let mut hide = (*t.hide).clone();
            hide.push(mac.id);
            let hide = Rc::new(hide);
            let use_span = t.tok.span;
            let Some(params) = &mac.params else {
                let body = self.substitute(&mac, &[], use_span, &hide, nesting);
                stack.extend(body.into_iter().rev());
                continue;
            };
            // Function-like: only a call when `(` follows.
            if !stack.last().is_some_and(|n| n.tok.is(Punct::LParen)) {
                out.push(t);
                continue;
            }
            stack.pop();
            let mut args: Vec<Vec<PTok>> = vec![Vec::new()];
            let mut level = 0usize;
            let mut close = None;
            while let Some(a) = stack.pop() {
                if a.tok.is(Punct::LParen) {
                    level += 1;
                } else if a.tok.is(Punct::RParen) {
                    if level == 0 {
                        close = Some(a.tok.span);
                        break;
                    }
                    level -= 1;
                } else if a.tok.is(Punct::Comma) && level == 0 && !(mac.variadic && args.len() == params.len()) {
                    args.push(Vec::new());
                    continue;
                }
                if let Some(last) = args.last_mut() {
                    last.push(a);
                }
            }
            let Some(close) = close else {
                self.error(
                    codes::MACRO_ARGS,
                    use_span,
                    format!("unterminated call of macro `{}`", t.tok.word().unwrap_or("")),
                )
                .with_label_mut("no `)` closes this macro call");
                break;
            };
            if params.is_empty() && args.len() == 1 && args[0].is_empty() {
                args.clear();
            }
            if mac.variadic && args.len() + 1 == params.len() {
                // No variable arguments: `__VA_ARGS__` is empty.
                args.push(Vec::new());
            }
            if args.len() != params.len() {
                let name = t.tok.word().unwrap_or("");
                self.error(
                    codes::MACRO_ARGS,
                    use_span.to(close),
                    format!("macro `{name}` takes {} argument(s) but {} were given", params.len(), args.len()),
                );
                // A `0` stands for the bad call so the parser does not report it a second time.
                let tok = Token { kind: TokenKind::Number(0.0), span: use_span.to(close), ..t.tok };
                out.push(PTok { tok, hide: t.hide });
                continue;
            }
            let body = self.substitute(&mac, &args, use_span.to(close), &hide, nesting);
            stack.extend(body.into_iter().rev());
        }
        out
    }

    /// The body of `mac` with parameters replaced by arguments, `#` and `##` applied; body
    /// tokens get the span `at` and hide set `hide`.
    fn substitute(&mut self, mac: &Macro, args: &[Vec<PTok>], at: Span, hide: &HideSet, nesting: usize) -> Vec<PTok> {
        let params: &[String] = mac.params.as_deref().unwrap_or(&[]);
        let param_of = |t: &Token| t.word().and_then(|w| params.iter().position(|p| p == w));
        let body = &mac.body;
        let mut out: Vec<PTok> = Vec::new();
        let mut expanded_args: Vec<Option<Vec<PTok>>> = vec![None; args.len()];
        let mut k = 0;
        while k < body.len() {
            let bt = &body[k];
            // `# param` → string
            if bt.is(Punct::Hash) && mac.params.is_some() {
                if let Some(p) = body.get(k + 1).and_then(param_of) {
                    let text = self.spelling(args.get(p).map_or(&[][..], |a| &a[..]));
                    let tok = Token { kind: TokenKind::Str(text), span: at, line_start: false, space_before: true };
                    out.push(PTok { tok, hide: hide.clone() });
                    k += 2;
                    continue;
                }
            }
            // `a ## b`
            if bt.is(Punct::HashHash) && !out.is_empty() {
                if let Some(next) = body.get(k + 1) {
                    let right: Vec<PTok> = match param_of(next) {
                        Some(p) => args.get(p).cloned().unwrap_or_default(),
                        None => vec![PTok { tok: Token { span: at, ..next.clone() }, hide: hide.clone() }],
                    };
                    if let Some(left) = out.pop() {
                        let joined =
                            format!("{}{}", self.spelling(&[left]), self.spelling(&right[..right.len().min(1)]));
                        out.extend(self.relex(&joined, at, hide));
                        out.extend(right.into_iter().skip(1));
                    }
                    k += 2;
                    continue;
                }
            }
            if let Some(p) = param_of(bt) {
                let pasted = body.get(k + 1).is_some_and(|n| n.is(Punct::HashHash));
                let arg = args.get(p).cloned().unwrap_or_default();
                if pasted {
                    out.extend(arg);
                } else {
                    if expanded_args[p].is_none() {
                        if nesting >= MAX_MACRO_NESTING {
                            self.abort(at, "macro calls nested too deeply in arguments");
                            return Vec::new();
                        }
                        expanded_args[p] = Some(self.expand(arg, nesting + 1));
                    }
                    out.extend(expanded_args[p].iter().flatten().cloned());
                }
                k += 1;
                continue;
            }
            let tok = Token { span: at, ..bt.clone() };
            out.push(PTok { tok, hide: hide.clone() });
            k += 1;
        }
        out
    }

    /// The source spelling of tokens, single-spaced where the source had space.
    fn spelling(&self, toks: &[PTok]) -> String {
        let mut s = String::new();
        for (n, t) in toks.iter().enumerate() {
            if n > 0 && t.tok.space_before {
                s.push(' ');
            }
            match &t.tok.kind {
                TokenKind::Ident(w) => s.push_str(w),
                TokenKind::Keyword(k) => s.push_str(k.as_str()),
                TokenKind::Punct(p) => s.push_str(p.as_str()),
                TokenKind::Number(v) => {
                    let src = self.sources.snippet(t.tok.span);
                    if src.parse::<f64>().ok() == Some(*v) {
                        s.push_str(src);
                    } else {
                        s.push_str(&v.to_string());
                    }
                }
                TokenKind::Str(v) => s.push_str(&format!("{v:?}")),
                TokenKind::Eof => {}
            }
        }
        s
    }

    /// Lexes pasted text; the tokens get span `at`.
    fn relex(&mut self, text: &str, at: Span, hide: &HideSet) -> Vec<PTok> {
        let (toks, errs) = lex(text, at.file);
        if !errs.is_empty() || toks.len() != 1 {
            self.error(codes::BAD_DIRECTIVE, at, format!("pasting with `##` gives `{text}`, which is not one token"));
        }
        toks.into_iter().map(|t| PTok { tok: Token { span: at, line_start: false, ..t }, hide: hide.clone() }).collect()
    }

    // ---- #if expressions --------------------------------------------------------------------

    fn eval_condition(&mut self, span: Span, args: &[Token]) -> bool {
        // `defined X` / `defined(X)` first, then macro expansion, then other names are 0.
        let empty: HideSet = Rc::new(Vec::new());
        let mut run = Vec::new();
        let mut k = 0;
        while k < args.len() {
            let t = &args[k];
            if t.word() == Some("defined") {
                let (name, len) = match (args.get(k + 1), args.get(k + 2), args.get(k + 3)) {
                    (Some(l), Some(n), Some(r)) if l.is(Punct::LParen) && r.is(Punct::RParen) => (n.word(), 4),
                    (Some(n), _, _) if n.word().is_some() => (n.word(), 2),
                    _ => (None, 1),
                };
                let Some(name) = name else {
                    self.error(codes::BAD_DIRECTIVE, t.span, "`defined` needs a macro name");
                    return false;
                };
                let v = if self.macros.contains_key(name) { 1.0 } else { 0.0 };
                run.push(PTok { tok: Token { kind: TokenKind::Number(v), ..t.clone() }, hide: empty.clone() });
                k += len;
                continue;
            }
            run.push(PTok { tok: t.clone(), hide: empty.clone() });
            k += 1;
        }
        let toks: Vec<Token> = self.expand(run, 0).into_iter().map(|p| p.tok).collect();
        if toks.is_empty() {
            self.error(codes::BAD_DIRECTIVE, span, "`#if` needs an expression");
            return false;
        }
        let mut ev = CondEval { toks: &toks, pos: 0, depth: 0 };
        match ev.ternary() {
            Ok(v) if ev.pos == toks.len() => v != 0.0,
            Ok(_) => {
                let at = toks[ev.pos].span;
                self.error(codes::BAD_DIRECTIVE, at, format!("unexpected {} in `#if` expression", toks[ev.pos].kind));
                false
            }
            Err(at) => {
                let at = at.unwrap_or(span);
                self.error(codes::BAD_DIRECTIVE, at, "malformed `#if` expression").notes.push(
                    "`#if` takes numbers, `defined(NAME)`, arithmetic, comparisons, `&&`, `||`, `!` and `?:`".into(),
                );
                false
            }
        }
    }
}

trait LabelMut {
    fn with_label_mut(&mut self, label: &str);
}

impl LabelMut for Diagnostic {
    fn with_label_mut(&mut self, label: &str) {
        self.label = label.to_owned();
    }
}

/// Evaluates a preprocessed `#if` expression over floats (C's integers are a subset).
struct CondEval<'t> {
    toks: &'t [Token],
    pos: usize,
    depth: usize,
}

/// `Err(Some(span))` points at the offending token; `None` means "at the end".
type CondResult = Result<f64, Option<Span>>;

impl CondEval<'_> {
    fn peek_punct(&self) -> Option<Punct> {
        match self.toks.get(self.pos).map(|t| &t.kind) {
            Some(TokenKind::Punct(p)) => Some(*p),
            _ => None,
        }
    }

    fn fail(&self) -> CondResult {
        Err(self.toks.get(self.pos).map(|t| t.span))
    }

    fn ternary(&mut self) -> CondResult {
        self.depth += 1;
        if self.depth > 200 {
            return self.fail();
        }
        let c = self.binary(0)?;
        let r = if self.peek_punct() == Some(Punct::Question) {
            self.pos += 1;
            let a = self.ternary()?;
            if self.peek_punct() != Some(Punct::Colon) {
                return self.fail();
            }
            self.pos += 1;
            let b = self.ternary()?;
            if c != 0.0 {
                a
            } else {
                b
            }
        } else {
            c
        };
        self.depth -= 1;
        Ok(r)
    }

    fn binary(&mut self, min: u8) -> CondResult {
        let mut l = self.unary()?;
        loop {
            let Some(p) = self.peek_punct() else { return Ok(l) };
            let prec = match p {
                Punct::OrOr => 1,
                Punct::AndAnd => 2,
                Punct::EqEq | Punct::Ne => 3,
                Punct::Lt | Punct::Le | Punct::Gt | Punct::Ge => 4,
                Punct::Plus | Punct::Minus => 5,
                Punct::Star | Punct::Slash => 6,
                _ => return Ok(l),
            };
            if prec <= min {
                return Ok(l);
            }
            self.pos += 1;
            let r = self.binary(prec)?;
            let b = |x: bool| if x { 1.0 } else { 0.0 };
            l = match p {
                Punct::OrOr => b(l != 0.0 || r != 0.0),
                Punct::AndAnd => b(l != 0.0 && r != 0.0),
                Punct::EqEq => b(l == r),
                Punct::Ne => b(l != r),
                Punct::Lt => b(l < r),
                Punct::Le => b(l <= r),
                Punct::Gt => b(l > r),
                Punct::Ge => b(l >= r),
                Punct::Plus => l + r,
                Punct::Minus => l - r,
                Punct::Star => l * r,
                // Division by zero gives 0 rather than an error (it only steers a condition).
                _ => {
                    if r == 0.0 {
                        0.0
                    } else {
                        l / r
                    }
                }
            };
        }
    }

    fn unary(&mut self) -> CondResult {
        self.depth += 1;
        if self.depth > 200 {
            return self.fail();
        }
        let Some(t) = self.toks.get(self.pos) else {
            return Err(None);
        };
        self.pos += 1;
        let v = match &t.kind {
            TokenKind::Number(v) => *v,
            // Names left after macro expansion are 0, as in C.
            TokenKind::Ident(_) | TokenKind::Keyword(_) => 0.0,
            TokenKind::Punct(Punct::Minus) => -self.unary()?,
            TokenKind::Punct(Punct::Plus) => self.unary()?,
            TokenKind::Punct(Punct::Not) => {
                if self.unary()? == 0.0 {
                    1.0
                } else {
                    0.0
                }
            }
            TokenKind::Punct(Punct::LParen) => {
                let v = self.ternary()?;
                if self.peek_punct() != Some(Punct::RParen) {
                    return self.fail();
                }
                self.pos += 1;
                v
            }
            _ => {
                self.pos -= 1;
                return self.fail();
            }
        };
        self.depth -= 1;
        Ok(v)
    }
}
