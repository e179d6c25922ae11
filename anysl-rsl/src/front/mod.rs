//! The front end: preprocessor, lexer, parser, checker and lowering to IR.

pub mod ast;
