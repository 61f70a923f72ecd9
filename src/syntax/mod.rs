//! Text → AST: the logical-line pass, the pest grammar and the tree builder.

pub mod ast;
pub mod lexer;
pub mod parser;

pub use parser::{parse_expr, parse_module, SyntaxError};
