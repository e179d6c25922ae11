//! The parser: preprocessed tokens → [`ast::Unit`].
//!
//! Recursive descent for definitions and statements, precedence climbing for binary operators.
//! The grammar is that of the RenderMan Interface Specification 3.2, Appendix B ("RenderMan
//! Shading Language Syntax Summary"), read leniently where real shaders are:
//!
//! * Formals: `;` separates type groups, `,` names within a group, a trailing `;` is allowed,
//!   and (as many shaders write C style) a `,` followed by a type starts a new group.
//! * Operator priority, lowest first: assignment `= += -= *= /=` (right-assoc), `?:`
//!   (right-assoc), `||`, `&&`, `== !=`, `< <= > >=`, `+ -`, `^`, `* /`, `.`, then the prefix
//!   operators (unary `-`, `!` and type casts), postfix `[ ]`, primaries.
//!   *Source for `.`, `^` and `*`*: RISpec 3.2 Appendix B lists `binop` "with priority
//!   decreasing as indicated" as `.`, then `/ *`, then `^`, then `+ -`; so `a * b . c` is
//!   `a * (b . c)` and `a ^ b * c` is `a ^ (b * c)`. The same appendix puts the unary operators
//!   "below the primary operators but higher than any binary or relational operator".
//! * Casts are the spec's `typecast expression`: `float x`, `color 1`, `point "world" (0,0,0)`,
//!   `color "hsv" (h, s, v)`, `matrix "shader" 1`; they bind like unary operators. A space name
//!   (a string literal) is only taken for `color`, `point`, `vector`, `normal` and `matrix`.
//!   The spec has no C-style `(float) x`, so neither does this parser.
//! * Parenthesized lists are triples (3) or matrix literals (16); `{…}` is an array initializer.
//! * `surface(…)`, `displacement(…)` etc. in expressions are calls of the message-passing
//!   functions, although the names are keywords.
//!
//! Errors are reported into [`Diagnostics`]; the parser then skips to the next `;` or `}` and
//! goes on, so one run shows several errors. Nesting (of expressions and statements) deeper
//! than [`MAX_NESTING`] is an error, so no input can overflow the stack.

use super::ast::*;
use super::lex::{Keyword as K, Punct as P, Token, TokenKind};
use crate::diag::{codes, Diagnostic, Diagnostics, Severity};
use crate::span::Span;
use crate::types::{BaseType, Detail};

/// Deepest nesting of expressions plus statements accepted.
pub const MAX_NESTING: usize = 256;

/// Parses a preprocessed token stream (as made by [`super::pp::preprocess`]; a missing final
/// end-of-file token is tolerated).
pub fn parse_tokens(tokens: &[Token], diags: &mut Diagnostics) -> Unit {
    let owned;
    let toks = if tokens.last().is_some_and(|t| t.kind == TokenKind::Eof) {
        tokens
    } else {
        let span = tokens.last().map_or(Span::DUMMY, |t| Span::new(t.span.file, t.span.end, t.span.end));
        let mut v = tokens.to_vec();
        v.push(Token { kind: TokenKind::Eof, span, line_start: true, space_before: true });
        owned = v;
        &owned[..]
    };
    let mut p = Parser { toks, pos: 0, diags, next_id: 0, depth: 0, too_deep: false, last_error_pos: usize::MAX };
    let items = p.unit();
    Unit { items, expr_count: p.next_id }
}

/// An error was reported; the caller recovers.
struct Fail;
type PResult<T> = Result<T, Fail>;

struct Parser<'t, 'd> {
    toks: &'t [Token],
    pos: usize,
    diags: &'d mut Diagnostics,
    next_id: u32,
    depth: usize,
    /// Nesting limit hit: everything after is skipped and no more errors are reported.
    too_deep: bool,
    /// Token index of the last error (one error per position).
    last_error_pos: usize,
}

fn type_keyword(k: K) -> Option<BaseType> {
    Some(match k {
        K::Float => BaseType::Float,
        K::Color => BaseType::Color,
        K::Point => BaseType::Point,
        K::Vector => BaseType::Vector,
        K::Normal => BaseType::Normal,
        K::Matrix => BaseType::Matrix,
        K::String => BaseType::String,
        K::Void => BaseType::Void,
        _ => return None,
    })
}

fn shader_keyword(k: K) -> Option<ShaderType> {
    Some(match k {
        K::Surface => ShaderType::Surface,
        K::Light => ShaderType::Light,
        K::Displacement => ShaderType::Displacement,
        K::Volume => ShaderType::Volume,
        K::Imager => ShaderType::Imager,
        _ => return None,
    })
}

impl Parser<'_, '_> {
    // ---- token access -------------------------------------------------------------------------

    fn peek(&self) -> &Token {
        // The stream ends with Eof and `bump` never moves past it.
        &self.toks[self.pos.min(self.toks.len() - 1)]
    }

    fn peek_at(&self, n: usize) -> &Token {
        &self.toks[(self.pos + n).min(self.toks.len() - 1)]
    }

    fn at_eof(&self) -> bool {
        self.peek().kind == TokenKind::Eof
    }

    fn bump(&mut self) -> &Token {
        let i = self.pos.min(self.toks.len() - 1);
        if !self.at_eof() {
            self.pos += 1;
        }
        &self.toks[i]
    }

    fn at(&self, p: P) -> bool {
        self.peek().is(p)
    }

    fn at_kw(&self, k: K) -> bool {
        self.peek().kind == TokenKind::Keyword(k)
    }

    fn eat(&mut self, p: P) -> bool {
        if self.at(p) {
            self.bump();
            true
        } else {
            false
        }
    }

    fn prev_span(&self) -> Span {
        self.toks[self.pos.saturating_sub(1).min(self.toks.len() - 1)].span
    }

    fn next_id(&mut self) -> ExprId {
        let id = ExprId(self.next_id);
        self.next_id = self.next_id.saturating_add(1);
        id
    }

    fn mk(&mut self, kind: ExprKind, span: Span) -> Expr {
        Expr { id: self.next_id(), kind, span }
    }

    // ---- errors -------------------------------------------------------------------------------

    /// Reports `expected {what}` at the next token.
    #[cold]
    fn expected(&mut self, what: &str) -> Fail {
        let t = self.peek().clone();
        if t.kind == TokenKind::Eof {
            self.report(
                Diagnostic::error(codes::UNEXPECTED_EOF, t.span, format!("unexpected end of file: expected {what}"))
                    .with_label("the file ends here"),
            );
        } else {
            self.report(
                Diagnostic::error(codes::SYNTAX, t.span, format!("expected {what}"))
                    .with_label(format!("found {}", t.kind)),
            );
        }
        Fail
    }

    #[cold]
    fn report(&mut self, d: Diagnostic) {
        if self.too_deep || (self.last_error_pos == self.pos && d.severity == Severity::Error) {
            return;
        }
        if d.severity == Severity::Error {
            self.last_error_pos = self.pos;
        }
        self.diags.push(d);
    }

    fn expect(&mut self, p: P, what: &str) -> PResult<Span> {
        if self.at(p) {
            Ok(self.bump().span)
        } else {
            Err(self.expected(what))
        }
    }

    fn enter(&mut self) -> PResult<()> {
        if self.too_deep {
            return Err(Fail);
        }
        self.depth += 1;
        if self.depth > MAX_NESTING {
            let span = self.peek().span;
            self.report(
                Diagnostic::error(codes::SYNTAX, span, format!("nesting too deep (more than {MAX_NESTING} levels)"))
                    .with_label("the limit is reached here")
                    .with_note("split the expression or statement into smaller pieces"),
            );
            self.too_deep = true;
            self.pos = self.toks.len() - 1;
            self.depth -= 1;
            return Err(Fail);
        }
        Ok(())
    }

    fn leave(&mut self) {
        self.depth = self.depth.saturating_sub(1);
    }

    /// Skips to just after the next `;` or to the `}` closing the statement's block, starting
    /// at `start` (the statement's first token) so braces opened inside it are balanced.
    fn recover_stmt(&mut self, start: usize) {
        let mut depth: i64 = 0;
        for t in &self.toks[start.min(self.pos)..self.pos] {
            if t.is(P::LBrace) {
                depth += 1;
            } else if t.is(P::RBrace) {
                depth -= 1;
            }
        }
        depth = depth.max(0);
        loop {
            let t = self.peek();
            if t.kind == TokenKind::Eof {
                return;
            }
            if t.is(P::Semi) && depth == 0 {
                self.bump();
                return;
            }
            if t.is(P::RBrace) {
                if depth == 0 {
                    return;
                }
                depth -= 1;
                self.bump();
                if depth == 0 {
                    // A statement ending in a block (`illuminate(…) { … }`) ends here.
                    return;
                }
                continue;
            }
            if t.is(P::LBrace) {
                depth += 1;
            }
            self.bump();
        }
    }

    /// Top level: skips past the broken definition (always consuming at least one token).
    fn recover_item(&mut self, start: usize) {
        let mut depth: i64 = 0;
        for t in &self.toks[start.min(self.pos)..self.pos] {
            if t.is(P::LBrace) {
                depth += 1;
            } else if t.is(P::RBrace) {
                depth -= 1;
            }
        }
        depth = depth.max(0);
        let mut consumed = self.pos > start;
        loop {
            let t = self.peek().clone();
            match &t.kind {
                TokenKind::Eof => return,
                TokenKind::Punct(P::Semi) if depth == 0 => {
                    self.bump();
                    return;
                }
                TokenKind::Punct(P::RBrace) => {
                    self.bump();
                    depth -= 1;
                    if depth <= 0 {
                        return;
                    }
                    continue;
                }
                TokenKind::Punct(P::LBrace) => depth += 1,
                TokenKind::Keyword(k)
                    if depth == 0
                        && consumed
                        && t.line_start
                        && (shader_keyword(*k).is_some() || type_keyword(*k).is_some()) =>
                {
                    return;
                }
                _ => {}
            }
            self.bump();
            consumed = true;
        }
    }

    // ---- definitions --------------------------------------------------------------------------

    fn unit(&mut self) -> Vec<Item> {
        let mut items = Vec::new();
        while !self.at_eof() {
            if self.eat(P::Semi) {
                continue;
            }
            let start = self.pos;
            match self.item() {
                Ok(it) => items.push(it),
                Err(Fail) => self.recover_item(start),
            }
        }
        items
    }

    fn item(&mut self) -> PResult<Item> {
        let t = self.peek().clone();
        match &t.kind {
            TokenKind::Keyword(k) if shader_keyword(*k).is_some() => {
                let kind = shader_keyword(*k).unwrap_or(ShaderType::Surface);
                self.bump();
                let name = self.ident("a shader name")?;
                let params = self.params(true)?;
                let body = self.block()?;
                let span = t.span.to(body.span);
                Ok(Item::Shader(ShaderDef { kind, name, params, body, span }))
            }
            TokenKind::Keyword(K::Uniform | K::Varying) => Ok(Item::Function(self.function()?)),
            TokenKind::Keyword(k) if type_keyword(*k).is_some() => {
                if self.peek_at(1).word().is_some() && !self.peek_at(2).is(P::LParen) {
                    let msg = "variables cannot be declared outside a shader or function";
                    self.report(
                        Diagnostic::error(codes::SYNTAX, t.span, msg).with_label("declaration at the top level"),
                    );
                    return Err(Fail);
                }
                Ok(Item::Function(self.function()?))
            }
            TokenKind::Ident(_) if self.peek_at(1).is(P::LParen) => Ok(Item::Function(self.function()?)),
            _ => Err(self.expected("a shader or function definition")),
        }
    }

    /// `[detail] type` (the detail and base as written).
    fn type_spec(&mut self) -> PResult<TypeSpec> {
        let start = self.peek().span;
        let detail = self.detail();
        match self.peek().kind {
            TokenKind::Keyword(k) if type_keyword(k).is_some() => {
                let base = type_keyword(k).unwrap_or(BaseType::Float);
                let span = start.to(self.bump().span);
                Ok(TypeSpec { detail, base, span })
            }
            _ => Err(self.expected("a type (`float`, `color`, `point`, `vector`, `normal`, `matrix`, `string`)")),
        }
    }

    fn detail(&mut self) -> Option<Detail> {
        if self.at_kw(K::Uniform) {
            self.bump();
            Some(Detail::Uniform)
        } else if self.at_kw(K::Varying) {
            self.bump();
            Some(Detail::Varying)
        } else {
            None
        }
    }

    /// `[[detail] type] name (formals) { body }`
    fn function(&mut self) -> PResult<FunctionDef> {
        let start = self.peek().span;
        let ret = if matches!(self.peek().kind, TokenKind::Ident(_)) {
            TypeSpec { detail: None, base: BaseType::Void, span: start }
        } else {
            self.type_spec()?
        };
        let name = self.ident("a function name")?;
        let params = self.params(false)?;
        let body = self.block()?;
        let span = start.to(body.span);
        Ok(FunctionDef { ret, name, params, body, span })
    }

    fn ident(&mut self, what: &str) -> PResult<Ident> {
        match &self.peek().kind {
            TokenKind::Ident(s) => {
                let name = s.clone();
                let span = self.bump().span;
                Ok(Ident { name, span })
            }
            _ => Err(self.expected(what)),
        }
    }

    /// A variable or parameter name: an identifier, or a shader-type word (`light`,
    /// `surface`, …), which shaders use as variable names (`color light = …` in Ivan
    /// DeWolf's IDscartissue.sl) — they are keywords only where a shader or a
    /// message-passing call can start.
    fn var_name(&mut self, what: &str) -> PResult<Ident> {
        match self.peek().kind {
            TokenKind::Keyword(k) if shader_keyword(k).is_some() => {
                let span = self.bump().span;
                Ok(Ident { name: k.as_str().to_owned(), span })
            }
            _ => self.ident(what),
        }
    }

    fn starts_formal(&self) -> bool {
        matches!(self.peek().kind, TokenKind::Keyword(k) if type_keyword(k).is_some() || matches!(k, K::Output | K::Uniform | K::Varying))
    }

    /// `( [formals] )`: groups `[output] [detail] type name [= default], …` separated by `;`.
    fn params(&mut self, shader: bool) -> PResult<Vec<Param>> {
        self.expect(P::LParen, "`(` to start the parameter list")?;
        let mut params = Vec::new();
        while !self.at(P::RParen) {
            let mut output = false;
            let mut detail = None;
            let start = self.peek().span;
            // `output` and the detail in either order.
            for _ in 0..2 {
                if self.at_kw(K::Output) {
                    self.bump();
                    output = true;
                } else if let Some(d) = self.detail() {
                    detail = Some(d);
                }
            }
            let mut ty = self.type_spec()?;
            if detail.is_some() {
                ty.detail = detail;
                ty.span = start.to(ty.span);
            }
            loop {
                let name = self.var_name("a parameter name")?;
                let array = if self.eat(P::LBracket) {
                    if self.eat(P::RBracket) {
                        Some(None)
                    } else {
                        let n = self.array_len()?;
                        self.expect(P::RBracket, "`]` after the array length")?;
                        Some(Some(n))
                    }
                } else {
                    None
                };
                let default = if self.eat(P::Assign) { Some(self.expr()?) } else { None };
                let span = name.span.to(default.as_ref().map_or(self.prev_span(), |d| d.span));
                if shader && default.is_none() {
                    self.report(
                        Diagnostic::error(
                            codes::SYNTAX,
                            name.span,
                            format!("shader parameter `{}` needs a default value", name.name),
                        )
                        .with_label("no `= value`")
                        .with_note(format!("write e.g. `{} {} = 0`", ty.base, name.name)),
                    );
                }
                params.push(Param { output, ty: ty.clone(), name, array, default, span });
                if self.at(P::Comma) {
                    self.bump();
                    if self.starts_formal() {
                        break; // C style `float a, float b`: a new group
                    }
                    continue;
                }
                break;
            }
            if self.eat(P::Semi) || self.starts_formal() {
                continue;
            }
            if !self.at(P::RParen) {
                return Err(self.expected("`;`, `,` or `)` in the parameter list"));
            }
        }
        self.bump();
        Ok(params)
    }

    /// An array length: a non-negative integer literal.
    fn array_len(&mut self) -> PResult<u32> {
        match self.peek().kind {
            TokenKind::Number(v) if v >= 0.0 && v.fract() == 0.0 && v <= f64::from(u32::MAX) => {
                self.bump();
                Ok(v as u32)
            }
            _ => Err(self.expected("an array length (a whole number)")),
        }
    }

    // ---- statements ---------------------------------------------------------------------------

    fn block(&mut self) -> PResult<Block> {
        let open = self.expect(P::LBrace, "`{`")?;
        let mut stmts = Vec::new();
        loop {
            if self.at(P::RBrace) {
                let close = self.bump().span;
                return Ok(Block { stmts, span: open.to(close) });
            }
            if self.at_eof() {
                let span = self.peek().span;
                self.report(
                    Diagnostic::error(codes::UNEXPECTED_EOF, span, "unexpected end of file: expected `}`")
                        .with_label("the file ends here")
                        .with_secondary(open, "to close this `{`"),
                );
                return Err(Fail);
            }
            let start = self.pos;
            match self.stmt() {
                Ok(s) => stmts.push(s),
                Err(Fail) => {
                    if self.too_deep {
                        return Err(Fail);
                    }
                    self.recover_stmt(start);
                }
            }
        }
    }

    fn stmt(&mut self) -> PResult<Stmt> {
        self.enter()?;
        let r = self.stmt_inner();
        self.leave();
        r
    }

    /// Dispatches on the first token. Each statement kind is parsed in its own function so that
    /// the frames on the recursion path (stmt → block → stmt …) stay small even in debug builds.
    fn stmt_inner(&mut self) -> PResult<Stmt> {
        let start = self.peek().span;
        let kind = match self.peek().kind {
            TokenKind::Punct(P::Semi) => {
                self.bump();
                Ok(StmtKind::Empty)
            }
            TokenKind::Punct(P::LBrace) => self.block().map(StmtKind::Block),
            TokenKind::Keyword(K::If) => self.if_stmt(),
            TokenKind::Keyword(K::While) => self.while_stmt(),
            TokenKind::Keyword(K::For) => self.for_stmt(),
            TokenKind::Keyword(k @ (K::Break | K::Continue)) => self.loop_mod_stmt(k),
            TokenKind::Keyword(K::Return) => self.return_stmt(),
            TokenKind::Keyword(K::Illuminance) => self.illuminance(),
            TokenKind::Keyword(K::Illuminate) => self.illuminate(),
            TokenKind::Keyword(K::Solar) => self.solar(),
            TokenKind::Keyword(K::Gather) => self.gather(),
            TokenKind::Keyword(K::Else) => Err(self.stray_else(start)),
            TokenKind::Keyword(K::Extern | K::Uniform | K::Varying | K::Output) => self.declaration(),
            TokenKind::Keyword(k) if type_keyword(k).is_some() && self.peek_at(1).word().is_some() => {
                self.declaration()
            }
            TokenKind::Ident(_) if self.peek_at(1).is(P::LParen) && self.is_untyped_function() => {
                self.function().map(|f| StmtKind::Function(Box::new(f)))
            }
            _ => self.expr_stmt(),
        }?;
        Ok(Stmt { kind, span: start.to(self.prev_span()) })
    }

    fn boxed_stmt(&mut self) -> PResult<Box<Stmt>> {
        self.stmt().map(Box::new)
    }

    /// `if (cond) stmt [else stmt]`
    fn if_stmt(&mut self) -> PResult<StmtKind> {
        self.bump();
        let cond = self.paren_cond("if")?;
        let then = self.boxed_stmt()?;
        let otherwise = if self.at_kw(K::Else) {
            self.bump();
            Some(self.boxed_stmt()?)
        } else {
            None
        };
        Ok(StmtKind::If { cond, then, otherwise })
    }

    fn while_stmt(&mut self) -> PResult<StmtKind> {
        self.bump();
        let cond = self.paren_cond("while")?;
        Ok(StmtKind::While { cond, body: self.boxed_stmt()? })
    }

    /// `for ([init]; [cond]; [step]) stmt`
    fn for_stmt(&mut self) -> PResult<StmtKind> {
        self.bump();
        self.expect(P::LParen, "`(` after `for`")?;
        if self.starts_formal() {
            let span = self.peek().span;
            self.report(
                Diagnostic::error(codes::SYNTAX, span, "declarations are not allowed in a `for` header")
                    .with_label("declare the variable before the loop"),
            );
            return Err(Fail);
        }
        let init = if self.at(P::Semi) { None } else { Some(self.expr()?) };
        self.expect(P::Semi, "`;` after the `for` initialization")?;
        let cond = if self.at(P::Semi) { None } else { Some(self.expr()?) };
        self.expect(P::Semi, "`;` after the `for` condition")?;
        let step = if self.at(P::RParen) { None } else { Some(self.expr()?) };
        self.expect(P::RParen, "`)` to close the `for` header")?;
        Ok(StmtKind::For { init, cond, step, body: self.boxed_stmt()? })
    }

    /// `break [n];` / `continue [n];`
    fn loop_mod_stmt(&mut self, k: K) -> PResult<StmtKind> {
        self.bump();
        let level = match self.peek().kind {
            TokenKind::Number(v) => {
                let span = self.bump().span;
                if v >= 1.0 && v.fract() == 0.0 && v <= f64::from(u32::MAX) {
                    Some(v as u32)
                } else {
                    self.report(
                        Diagnostic::error(codes::SYNTAX, span, format!("bad loop level `{v}`"))
                            .with_label("must be a whole number ≥ 1"),
                    );
                    return Err(Fail);
                }
            }
            _ => None,
        };
        self.expect(P::Semi, &format!("`;` after `{}`", k.as_str()))?;
        Ok(if k == K::Break { StmtKind::Break(level) } else { StmtKind::Continue(level) })
    }

    fn return_stmt(&mut self) -> PResult<StmtKind> {
        self.bump();
        let value = if self.at(P::Semi) { None } else { Some(self.expr()?) };
        self.expect(P::Semi, "`;` after the return value")?;
        Ok(StmtKind::Return(value))
    }

    /// `illuminate(position [, axis, angle]) stmt`
    fn illuminate(&mut self) -> PResult<StmtKind> {
        self.bump();
        let (mut args, span) = self.loop_args("illuminate")?;
        let cone = match args.len() {
            1 => None,
            3 => {
                let angle = args.pop();
                args.pop().zip(angle)
            }
            n => return Err(self.arg_count_error(span, "illuminate", "1 or 3", n)),
        };
        let Some(position) = args.pop() else { return Err(Fail) };
        Ok(StmtKind::Illuminate { position, cone, body: self.boxed_stmt()? })
    }

    /// `solar([axis, angle]) stmt`
    fn solar(&mut self) -> PResult<StmtKind> {
        self.bump();
        let (mut args, span) = self.loop_args("solar")?;
        let cone = match args.len() {
            0 => None,
            2 => {
                let angle = args.pop();
                args.pop().zip(angle)
            }
            n => return Err(self.arg_count_error(span, "solar", "0 or 2", n)),
        };
        Ok(StmtKind::Solar { cone, body: self.boxed_stmt()? })
    }

    /// `gather(args…) stmt [else stmt]`
    fn gather(&mut self) -> PResult<StmtKind> {
        self.bump();
        let (args, _) = self.loop_args("gather")?;
        let body = self.boxed_stmt()?;
        let otherwise = if self.at_kw(K::Else) {
            self.bump();
            Some(self.boxed_stmt()?)
        } else {
            None
        };
        Ok(StmtKind::Gather { args, body, otherwise })
    }

    #[cold]
    fn stray_else(&mut self, start: Span) -> Fail {
        self.report(
            Diagnostic::error(codes::SYNTAX, start, "`else` without `if`")
                .with_label("no `if` before this `else`")
                .with_note("is there a `;` after the `if` body's closing `}` or a missing `{`?"),
        );
        self.bump();
        Fail
    }

    fn expr_stmt(&mut self) -> PResult<StmtKind> {
        let e = self.expr()?;
        self.expect(P::Semi, "`;` after expression")?;
        Ok(StmtKind::Expr(e))
    }

    /// `name ( … ) {` — a nested function definition without a return type.
    fn is_untyped_function(&self) -> bool {
        let mut level = 0usize;
        let mut i = self.pos + 1;
        while let Some(t) = self.toks.get(i) {
            match t.kind {
                TokenKind::Punct(P::LParen) => level += 1,
                TokenKind::Punct(P::RParen) => {
                    level = level.saturating_sub(1);
                    if level == 0 {
                        return self.toks.get(i + 1).is_some_and(|t| t.is(P::LBrace));
                    }
                }
                TokenKind::Punct(P::Semi | P::LBrace | P::RBrace) | TokenKind::Eof => return false,
                _ => {}
            }
            i += 1;
        }
        false
    }

    /// `[extern] [detail] [output] type name …` — a declaration, or a nested function.
    fn declaration(&mut self) -> PResult<StmtKind> {
        let is_extern = if self.at_kw(K::Extern) {
            self.bump();
            true
        } else {
            false
        };
        let out_span = self.peek().span;
        let output = if self.at_kw(K::Output) {
            self.bump();
            true
        } else {
            false
        };
        let ty = self.type_spec()?;
        if output || self.at_kw(K::Output) {
            self.report(
                Diagnostic::error(codes::SYNTAX, out_span, "`output` is only allowed on parameters")
                    .with_label("not a parameter"),
            );
            return Err(Fail);
        }
        if !is_extern && self.peek_at(1).is(P::LParen) && matches!(self.peek().kind, TokenKind::Ident(_)) {
            // Nested function definition.
            let name = self.ident("a function name")?;
            let params = self.params(false)?;
            let body = self.block()?;
            let span = ty.span.to(body.span);
            return Ok(StmtKind::Function(Box::new(FunctionDef { ret: ty, name, params, body, span })));
        }
        let mut vars = Vec::new();
        loop {
            let name = self.var_name("a variable name")?;
            let mut unsized_at = None;
            let mut array = if self.eat(P::LBracket) {
                if self.at(P::RBracket) {
                    unsized_at = Some(self.bump().span);
                    Some(0)
                } else {
                    let n = self.array_len()?;
                    self.expect(P::RBracket, "`]` after the array length")?;
                    Some(n)
                }
            } else {
                None
            };
            let init = if self.eat(P::Assign) { Some(self.expr()?) } else { None };
            // `float a[] = {1, 2, 3}`: the length comes from the initializer.
            if let Some(at) = unsized_at {
                match init.as_ref().map(|e| &e.kind) {
                    Some(ExprKind::ArrayInit(v)) => array = Some(u32::try_from(v.len()).unwrap_or(u32::MAX)),
                    _ => {
                        self.report(
                            Diagnostic::error(codes::SYNTAX, at, format!("array `{}` needs a length", name.name))
                                .with_label("no length here")
                                .with_note(
                                    "write the length, `float a[3]`, or an initializer, `float a[] = {1, 2, 3}`",
                                ),
                        );
                        return Err(Fail);
                    }
                }
            }
            let span = name.span.to(self.prev_span());
            vars.push(Declarator { name, array, init, span });
            if !self.eat(P::Comma) {
                break;
            }
        }
        self.expect(P::Semi, "`;` after the declaration")?;
        Ok(StmtKind::Decl { is_extern, ty, vars })
    }

    fn paren_cond(&mut self, what: &str) -> PResult<Expr> {
        self.expect(P::LParen, &format!("`(` after `{what}`"))?;
        let e = self.expr()?;
        self.expect(P::RParen, &format!("`)` after the `{what}` condition"))?;
        Ok(e)
    }

    /// `( [expr {, expr}] )` after a loop keyword; returns the arguments and the list's span.
    fn loop_args(&mut self, what: &str) -> PResult<(Vec<Expr>, Span)> {
        let open = self.expect(P::LParen, &format!("`(` after `{what}`"))?;
        let args = self.expr_list(P::RParen, "`,` or `)`")?;
        Ok((args, open.to(self.prev_span())))
    }

    #[cold]
    fn arg_count_error(&mut self, span: Span, what: &str, want: &str, got: usize) -> Fail {
        self.report(
            Diagnostic::error(codes::SYNTAX, span, format!("`{what}` takes {want} arguments, not {got}"))
                .with_label("wrong number of arguments"),
        );
        Fail
    }

    /// `illuminance([category,] position [, axis, angle]) stmt`
    fn illuminance(&mut self) -> PResult<StmtKind> {
        self.bump();
        let (args, span) = self.loop_args("illuminance")?;
        let first_is_string = matches!(args.first().map(|e| &e.kind), Some(ExprKind::Str(_)));
        let n = args.len();
        // 1: P; 2: category, P; 3: P, axis, angle; 4: category, P, axis, angle. More: the
        // PRMan message-passing extras after those, recognised by a leading string category.
        let (with_category, base) = match n {
            0 => return Err(self.arg_count_error(span, "illuminance", "1 to 4", 0)),
            1 | 3 => (false, n),
            2 | 4 => (true, n),
            _ if first_is_string => (true, 4),
            _ => (false, 3),
        };
        if n > base {
            self.report(
                Diagnostic::warning(
                    codes::UNSUPPORTED,
                    args[base].span.to(args[n - 1].span),
                    "extra `illuminance` arguments are ignored",
                )
                .with_label("ignored")
                .with_note("RSL 3.2 `illuminance` takes [category,] position [, axis, angle]"),
            );
        }
        let mut it = args.into_iter().take(base);
        let category = if with_category { it.next() } else { None };
        let Some(position) = it.next() else { return Err(Fail) };
        let cone = match (it.next(), it.next()) {
            (Some(a), Some(b)) => Some((a, b)),
            _ => None,
        };
        Ok(StmtKind::Illuminance { category, position, cone, body: self.boxed_stmt()? })
    }

    // ---- expressions --------------------------------------------------------------------------

    /// A full expression (assignment level).
    fn expr(&mut self) -> PResult<Expr> {
        self.enter()?;
        let r = self.assignment();
        self.leave();
        r
    }

    fn assignment(&mut self) -> PResult<Expr> {
        let lhs = self.ternary()?;
        let op = match self.peek().kind {
            TokenKind::Punct(P::Assign) => AssignOp::Assign,
            TokenKind::Punct(P::PlusAssign) => AssignOp::Add,
            TokenKind::Punct(P::MinusAssign) => AssignOp::Sub,
            TokenKind::Punct(P::StarAssign) => AssignOp::Mul,
            TokenKind::Punct(P::SlashAssign) => AssignOp::Div,
            _ => return Ok(lhs),
        };
        self.bump();
        let rhs = self.expr()?;
        let span = lhs.span.to(rhs.span);
        Ok(self.mk(ExprKind::Assign(op, Box::new(lhs), Box::new(rhs)), span))
    }

    fn ternary(&mut self) -> PResult<Expr> {
        let cond = self.binary(0)?;
        if !self.eat(P::Question) {
            return Ok(cond);
        }
        let a = self.expr()?;
        self.expect(P::Colon, "`:` in the `?:` expression")?;
        self.enter()?;
        let b = self.ternary();
        self.leave();
        let b = b?;
        let span = cond.span.to(b.span);
        Ok(self.mk(ExprKind::Ternary(Box::new(cond), Box::new(a), Box::new(b)), span))
    }

    fn binop(&self) -> Option<(BinaryOp, u8)> {
        let TokenKind::Punct(p) = self.peek().kind else {
            return None;
        };
        Some(match p {
            P::OrOr => (BinaryOp::Or, 1),
            P::AndAnd => (BinaryOp::And, 2),
            P::EqEq => (BinaryOp::Eq, 3),
            P::Ne => (BinaryOp::Ne, 3),
            P::Lt => (BinaryOp::Lt, 4),
            P::Le => (BinaryOp::Le, 4),
            P::Gt => (BinaryOp::Gt, 4),
            P::Ge => (BinaryOp::Ge, 4),
            P::Plus => (BinaryOp::Add, 5),
            P::Minus => (BinaryOp::Sub, 5),
            P::Caret => (BinaryOp::Cross, 6),
            P::Star => (BinaryOp::Mul, 7),
            P::Slash => (BinaryOp::Div, 7),
            P::Dot => (BinaryOp::Dot, 8),
            _ => return None,
        })
    }

    /// Precedence climbing over left-associative binary operators binding tighter than `min`.
    fn binary(&mut self, min: u8) -> PResult<Expr> {
        let mut lhs = self.unary()?;
        while let Some((op, prec)) = self.binop() {
            if prec <= min {
                break;
            }
            self.bump();
            let rhs = self.binary(prec)?;
            let span = lhs.span.to(rhs.span);
            lhs = self.mk(ExprKind::Binary(op, Box::new(lhs), Box::new(rhs)), span);
        }
        Ok(lhs)
    }

    fn unary(&mut self) -> PResult<Expr> {
        self.enter()?;
        let r = self.unary_inner();
        self.leave();
        r
    }

    fn unary_inner(&mut self) -> PResult<Expr> {
        let t = self.peek().clone();
        match t.kind {
            TokenKind::Punct(p @ (P::Minus | P::Not)) => {
                self.bump();
                let e = self.unary()?;
                let op = if p == P::Minus { UnaryOp::Neg } else { UnaryOp::Not };
                let span = t.span.to(e.span);
                Ok(self.mk(ExprKind::Unary(op, Box::new(e)), span))
            }
            // Unary `+` is not in the spec but harmless: it is the operand itself.
            TokenKind::Punct(P::Plus) => {
                self.bump();
                self.unary()
            }
            TokenKind::Keyword(k) if type_keyword(k).is_some() => {
                let to = type_keyword(k).unwrap_or(BaseType::Float);
                self.bump();
                if to == BaseType::Void {
                    self.report(
                        Diagnostic::error(codes::SYNTAX, t.span, "cannot cast to `void`")
                            .with_label("not a value type"),
                    );
                    return Err(Fail);
                }
                let space = match &self.peek().kind {
                    TokenKind::Str(s) if to.is_triple() || to == BaseType::Matrix => {
                        let s = s.clone();
                        let span = self.bump().span;
                        Some(Box::new(self.mk(ExprKind::Str(s), span)))
                    }
                    _ => None,
                };
                let e = self.unary()?;
                let span = t.span.to(e.span);
                Ok(self.mk(ExprKind::Cast { to, space, expr: Box::new(e) }, span))
            }
            _ => self.postfix(),
        }
    }

    fn postfix(&mut self) -> PResult<Expr> {
        let mut e = self.primary()?;
        while self.eat(P::LBracket) {
            let index = self.expr()?;
            let close = self.expect(P::RBracket, "`]` after the index")?;
            let span = e.span.to(close);
            e = self.mk(ExprKind::Index(Box::new(e), Box::new(index)), span);
        }
        // `x++`, `x--` (C increments, as PRMan 13+ and 3Delight accept): `(x += 1) - 1`.
        if let Some(op) = self.incdec_at(0) {
            if matches!(e.kind, ExprKind::Name(_) | ExprKind::Index(..)) {
                self.bump();
                self.bump();
                let span = e.span.to(self.prev_span());
                let one = self.mk(ExprKind::Number(1.0), span);
                let assign = self.mk(ExprKind::Assign(op, Box::new(e), Box::new(one)), span);
                let one = self.mk(ExprKind::Number(1.0), span);
                let undo = if op == AssignOp::Add { BinaryOp::Sub } else { BinaryOp::Add };
                e = self.mk(ExprKind::Binary(undo, Box::new(assign), Box::new(one)), span);
            }
        }
        Ok(e)
    }

    /// `++` or `--` at token `n`: two adjacent `+` (or `-`) tokens.
    fn incdec_at(&self, n: usize) -> Option<AssignOp> {
        let (a, b) = (self.peek_at(n), self.peek_at(n + 1));
        let op = match (&a.kind, &b.kind) {
            (TokenKind::Punct(P::Plus), TokenKind::Punct(P::Plus)) => AssignOp::Add,
            (TokenKind::Punct(P::Minus), TokenKind::Punct(P::Minus)) => AssignOp::Sub,
            _ => return None,
        };
        (a.span.file == b.span.file && a.span.end == b.span.start).then_some(op)
    }

    /// `expr {, expr} close` (the list may be empty); consumes `close`.
    fn expr_list(&mut self, close: P, what: &str) -> PResult<Vec<Expr>> {
        let mut list = Vec::new();
        if self.eat(close) {
            return Ok(list);
        }
        loop {
            list.push(self.expr()?);
            if self.eat(close) {
                return Ok(list);
            }
            if !self.eat(P::Comma) {
                return Err(self.expected(what));
            }
        }
    }

    fn primary(&mut self) -> PResult<Expr> {
        let t = self.peek().clone();
        match &t.kind {
            TokenKind::Number(v) => {
                self.bump();
                Ok(self.mk(ExprKind::Number(*v), t.span))
            }
            TokenKind::Str(s) => {
                self.bump();
                Ok(self.mk(ExprKind::Str(s.clone()), t.span))
            }
            TokenKind::Ident(name) => {
                self.bump();
                if self.at(P::LParen) {
                    self.call(Ident { name: name.clone(), span: t.span })
                } else {
                    Ok(self.mk(ExprKind::Name(name.clone()), t.span))
                }
            }
            // `surface("Kd", x)`, `displacement(…)`: message-passing functions.
            TokenKind::Keyword(k) if shader_keyword(*k).is_some() && self.peek_at(1).is(P::LParen) => {
                self.bump();
                self.call(Ident { name: k.as_str().to_owned(), span: t.span })
            }
            // A variable named like a shader type (see `var_name`).
            TokenKind::Keyword(k) if shader_keyword(*k).is_some() => {
                self.bump();
                Ok(self.mk(ExprKind::Name(k.as_str().to_owned()), t.span))
            }
            TokenKind::Punct(P::LParen) => {
                self.bump();
                let first = self.expr()?;
                if self.eat(P::RParen) {
                    return Ok(first);
                }
                if !self.at(P::Comma) {
                    return Err(self.expected("`)` or `,`"));
                }
                self.bump();
                let mut list = vec![first];
                list.extend(self.expr_list(P::RParen, "`,` or `)` in the parenthesized list")?);
                let span = t.span.to(self.prev_span());
                match list.len() {
                    3 => {
                        let mut it = list.into_iter();
                        match (it.next(), it.next(), it.next()) {
                            (Some(a), Some(b), Some(c)) => Ok(self.mk(ExprKind::Triple(Box::new([a, b, c])), span)),
                            _ => Err(Fail),
                        }
                    }
                    16 => Ok(self.mk(ExprKind::MatrixLit(list), span)),
                    n => {
                        self.report(
                            Diagnostic::error(
                                codes::BAD_LITERAL,
                                span,
                                format!("a parenthesized list has 3 or 16 components, not {n}"),
                            )
                            .with_label("neither a triple nor a matrix")
                            .with_note("write `(x, y, z)` for a point/vector/normal/color or 16 numbers for a matrix"),
                        );
                        Err(Fail)
                    }
                }
            }
            TokenKind::Punct(P::LBrace) => {
                self.bump();
                let list = self.expr_list_trailing_comma()?;
                let span = t.span.to(self.prev_span());
                Ok(self.mk(ExprKind::ArrayInit(list), span))
            }
            _ => Err(self.expected("an expression")),
        }
    }

    /// `{ a, b, c }` contents (a trailing comma allowed); consumes `}`.
    fn expr_list_trailing_comma(&mut self) -> PResult<Vec<Expr>> {
        let mut list = Vec::new();
        loop {
            if self.eat(P::RBrace) {
                return Ok(list);
            }
            list.push(self.expr()?);
            if self.eat(P::RBrace) {
                return Ok(list);
            }
            if !self.eat(P::Comma) {
                return Err(self.expected("`,` or `}` in the array initializer"));
            }
        }
    }

    fn call(&mut self, name: Ident) -> PResult<Expr> {
        self.expect(P::LParen, "`(`")?;
        let args = self.expr_list(P::RParen, "`,` or `)` in the argument list")?;
        let span = name.span.to(self.prev_span());
        Ok(self.mk(ExprKind::Call(name, args), span))
    }
}
