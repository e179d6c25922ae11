//! Names: the scope stack (variables, read-only values and nested functions, with the
//! barrier of a function body that only `extern` crosses), name look-up after the scopes
//! (globals, `PI`), and the loop and frame contexts of the enclosing control flow.

use super::typing::global_access;
use super::{Lowerer, Val};
use crate::diag::{codes, Diagnostic};
use crate::front::ast::{self, ShaderType};
use crate::ir::{Global, SlotId};
use crate::span::Span;
use std::collections::HashMap;

#[derive(Clone, Copy, Debug)]
pub(super) enum Binding {
    /// A variable.
    Slot(SlotId),
    /// A read-only value (non-output function parameter).
    Value(Val),
}

#[derive(Clone, Copy, Debug)]
pub(super) struct VarInfo {
    pub(super) binding: Binding,
    pub(super) span: Span,
    /// Read-only (non-output parameters, including array ones bound to the caller's slot).
    pub(super) read_only: bool,
    /// Varying-flow depth at the declaration.
    pub(super) flow: u32,
}

#[derive(Default)]
pub(super) struct Scope<'a> {
    pub(super) vars: HashMap<String, VarInfo>,
    pub(super) funcs: HashMap<String, Vec<&'a ast::FunctionDef>>,
    /// Names above this scope cannot see names below it (a function body), except via extern.
    barrier: bool,
}

pub(super) struct LoopCtx {
    /// A varying `break`/`continue` left some lanes behind.
    pub(super) varying: bool,
}

pub(super) struct FrameCtx<'a> {
    pub(super) func: Option<&'a ast::FunctionDef>,
    pub(super) ret_slot: Option<SlotId>,
    pub(super) loops: Vec<LoopCtx>,
    /// A varying `return` ended some lanes early.
    pub(super) varying_exit: bool,
    /// The varying-flow depth at the frame's start.
    pub(super) flow_at_entry: u32,
}

/// Found by a name look-up.
pub(super) enum Found {
    Var(VarInfo),
    Global(Global),
    Pi,
}

impl<'a, 'd> Lowerer<'a, 'd> {
    pub(super) fn push_scope(&mut self, barrier: bool) {
        self.scopes.push(Scope { barrier, ..Scope::default() });
    }

    pub(super) fn pop_scope(&mut self) {
        self.scopes.pop();
    }

    /// The current varying-flow depth (conditions plus varying early exits).
    pub(super) fn flow(&self) -> u32 {
        let exits: u32 = self
            .frames
            .iter()
            .map(|f| u32::from(f.varying_exit) + f.loops.iter().filter(|l| l.varying).count() as u32)
            .sum();
        self.vflow + exits
    }

    pub(super) fn frame(&mut self) -> Option<&mut FrameCtx<'a>> {
        self.frames.last_mut()
    }

    pub(super) fn declare(&mut self, name: &str, info: VarInfo) {
        let prev = self.scopes.last().and_then(|s| s.vars.get(name)).map(|v| v.span);
        if let Some(prev) = prev {
            self.report(
                Diagnostic::error(codes::REDEFINITION, info.span, format!("`{name}` is already defined in this scope"))
                    .with_label("redefined here")
                    .with_secondary(prev, "first defined here")
                    .with_note("rename one of them, or assign to the existing variable without a type"),
            );
            return;
        }
        if let Some(s) = self.scopes.last_mut() {
            s.vars.insert(name.to_string(), info);
        }
    }

    pub(super) fn lookup(&self, name: &str) -> Option<Found> {
        for s in self.scopes.iter().rev() {
            if let Some(v) = s.vars.get(name) {
                return Some(Found::Var(*v));
            }
            if s.barrier {
                break;
            }
        }
        if let Some(g) = Global::from_name(name) {
            return Some(Found::Global(g));
        }
        // Aqsis' light shaders call the surface normal at `Ps` `Ns`.
        if name == "Ns" && self.kind == ShaderType::Light {
            return Some(Found::Global(Global::N));
        }
        if name == "PI" {
            return Some(Found::Pi);
        }
        None
    }

    /// `extern` look-up: past function barriers.
    pub(super) fn lookup_extern(&self, name: &str) -> Option<Found> {
        let mut crossed = false;
        for s in self.scopes.iter().rev() {
            if crossed {
                if let Some(v) = s.vars.get(name) {
                    return Some(Found::Var(*v));
                }
            }
            if s.barrier {
                crossed = true;
            }
        }
        Global::from_name(name).map(Found::Global)
    }

    pub(super) fn visible_names(&self) -> Vec<String> {
        let mut out = Vec::new();
        for s in self.scopes.iter().rev() {
            out.extend(s.vars.keys().cloned());
            if s.barrier {
                break;
            }
        }
        out.extend(Global::ALL.iter().filter(|(g, _)| global_access(self.kind, *g).0).map(|(_, n)| n.to_string()));
        out.push("PI".into());
        out
    }

    pub(super) fn lookup_fns(&self, name: &str) -> Vec<&'a ast::FunctionDef> {
        let mut out = Vec::new();
        for s in self.scopes.iter().rev() {
            if let Some(f) = s.funcs.get(name) {
                out.extend(f.iter().copied());
            }
        }
        out
    }

    pub(super) fn declare_fn(&mut self, f: &'a ast::FunctionDef) {
        let sig = |f: &ast::FunctionDef| {
            f.params.iter().map(|p| (p.ty.base, p.array.is_some(), p.output)).collect::<Vec<_>>()
        };
        let mine = sig(f);
        let prev = self
            .scopes
            .last()
            .and_then(|s| s.funcs.get(&f.name.name))
            .and_then(|v| v.iter().find(|g| sig(g) == mine && g.span != f.span))
            .map(|g| g.name.span);
        if let Some(prev) = prev {
            self.report(
                Diagnostic::error(
                    codes::REDEFINITION,
                    f.name.span,
                    format!("function `{}` is already defined with these parameter types", f.name.name),
                )
                .with_label("redefined here")
                .with_secondary(prev, "first defined here")
                .with_note("functions may share a name only when their parameter types differ"),
            );
            return;
        }
        if let Some(s) = self.scopes.last_mut() {
            s.funcs.entry(f.name.name.clone()).or_default().push(f);
        }
    }
}
