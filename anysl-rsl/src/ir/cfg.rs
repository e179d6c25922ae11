//! The control-flow graph view of a structured body.
