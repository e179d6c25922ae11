//! IR passes: specialization of uniform parameters with constant folding, dead-code
//! elimination, uniform/varying analysis and derivative-activity analysis.
//!
//! [`optimize`] runs them in that order and returns an [`Analyzed`] module: the one thing the
//! back ends (the interpreter's [`crate::back::interp::Program`], the Rust generator, the
//! JIT) take, so none of them can be handed a module whose analyses have not run.
//!
//! [`lights`] is an analysis a back end runs on an analyzed module for itself, not a pass:
//! which calls of the built-in light loops can share one visit of the lights.

pub mod analysis;
pub mod dce;
pub mod fold;
pub mod lights;

use crate::ir::{Const, Module};

/// Which passes [`optimize`] runs.
#[derive(Clone, Debug, PartialEq)]
pub struct PassOptions {
    /// Replace reads of uniform parameters by these values (name, value); parameters not
    /// listed keep their run-time value unless `specialize_defaults` is set.
    pub specialize: Vec<(String, Const)>,
    /// Also treat every unlisted uniform parameter as its default (a fixed instance).
    pub specialize_defaults: bool,
    /// Fold constants (also folds away branches on constants).
    pub fold: bool,
    /// Remove dead code.
    pub dce: bool,
}

impl Default for PassOptions {
    fn default() -> Self {
        Self { specialize: Vec::new(), specialize_defaults: false, fold: true, dce: true }
    }
}

/// Instruction counts after each stage.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct PassReport {
    /// `(stage, instructions placed in the body)`, starting with `("lowered", n)`.
    pub stages: Vec<(&'static str, usize)>,
    /// True when some value needs derivatives (the shader must run on dual numbers).
    pub uses_derivatives: bool,
}

/// A module after [`optimize`]: passes run, every instruction's uniform/varying detail and
/// derivative need set. Only [`optimize`] makes one.
#[derive(Clone, Debug)]
pub struct Analyzed {
    module: Module,
    report: PassReport,
}

impl Analyzed {
    /// The analyzed module.
    #[must_use]
    pub fn module(&self) -> &Module {
        &self.module
    }

    /// What the passes did and found.
    #[must_use]
    pub fn report(&self) -> &PassReport {
        &self.report
    }

    /// True when some value needs derivatives (the shader must run on dual numbers).
    #[must_use]
    pub fn uses_derivatives(&self) -> bool {
        self.report.uses_derivatives
    }

    /// The module, for a back end that keeps it.
    #[must_use]
    pub fn into_module(self) -> Module {
        self.module
    }
}

/// Runs the passes, then the analyses (always: back ends rely on them).
#[must_use]
pub fn optimize(mut module: Module, opts: &PassOptions) -> Analyzed {
    let mut report = PassReport::default();
    report.stages.push(("lowered", module.func.inst_count()));
    if !opts.specialize.is_empty() || opts.specialize_defaults {
        fold::specialize(&mut module, &opts.specialize, opts.specialize_defaults);
        report.stages.push(("specialized", module.func.inst_count()));
    }
    if opts.fold {
        fold::fold_constants(&mut module.func);
        report.stages.push(("folded", module.func.inst_count()));
    }
    if opts.dce {
        dce::eliminate_dead_code(&mut module);
        report.stages.push(("dce", module.func.inst_count()));
    }
    analysis::analyze_uniform(&mut module.func);
    // A displacement's P and N leave it with their derivatives (bump mapping reads them).
    let outputs: &[crate::ir::Global] = match module.kind {
        crate::ir::ShaderKind::Displacement => &[crate::ir::Global::P, crate::ir::Global::N],
        _ => &[],
    };
    report.uses_derivatives = analysis::analyze_derivatives(&mut module.func, outputs);
    Analyzed { module, report }
}
