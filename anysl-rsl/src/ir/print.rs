//! The readable IR printer.
