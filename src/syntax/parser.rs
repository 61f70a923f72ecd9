//! pest parse tree → [`ast`](super::ast).

use super::ast::*;
use super::lexer::logical_lines;
use pest::iterators::Pair;
use pest::Parser;
use std::rc::Rc;

#[derive(pest_derive::Parser)]
#[grammar = "../grammar/comm.pest"]
struct CommParser;

/// A syntax error at a byte offset of the source.
#[derive(Debug, Clone)]
pub struct SyntaxError {
    pub offset: usize,
    pub message: String,
}

type PResult<T> = Result<T, SyntaxError>;

fn err<T>(offset: usize, message: impl Into<String>) -> PResult<T> {
    Err(SyntaxError { offset, message: message.into() })
}

/// Brackets nested deeper than this are refused (Python's own limit is 200).
pub const MAX_NESTING: usize = 100;

/// Parse a whole command file.
pub fn parse_module(src: &str) -> PResult<Module> {
    if let Some(at) = super::lexer::too_deep(src, MAX_NESTING) {
        return err(at, format!("invalid syntax: brackets nested more than {MAX_NESTING} deep"));
    }
    let text = logical_lines(src);
    let mut pairs = CommParser::parse(Rule::file, &text).map_err(|e| from_pest(src, &text, e))?;
    let file = pairs.next().unwrap();
    let mut body = Vec::new();
    for p in file.into_inner() {
        if p.as_rule() == Rule::EOI {
            break;
        }
        stmt(p, &mut body)?;
    }
    Ok(Module { body })
}

/// Parse a standalone expression (FORMULE bodies, f-string fields). `base` is
/// added to every span so that errors point into the enclosing file.
pub fn parse_expr(src: &str, base: usize) -> PResult<Expr> {
    if let Some(at) = super::lexer::too_deep(src, MAX_NESTING) {
        return err(base + at, format!("invalid syntax: brackets nested more than {MAX_NESTING} deep"));
    }
    let text = logical_lines(src);
    let mut pairs = CommParser::parse(Rule::expr_only, &text).map_err(|e| {
        let mut e = from_pest(src, &text, e);
        e.offset += base;
        e
    })?;
    let p = pairs.next().unwrap().into_inner().next().unwrap();
    let mut e = testlist(p)?;
    shift_span(&mut e, base);
    Ok(e)
}

fn shift_span(e: &mut Expr, base: usize) {
    if base == 0 {
        return;
    }
    // Spans are only used for messages; shifting the root is enough for the
    // located errors we raise from FORMULE and f-string evaluation.
    e.span.start += base;
    e.span.end += base;
}

fn from_pest(src: &str, text: &str, e: pest::error::Error<Rule>) -> SyntaxError {
    let offset = match e.location {
        pest::error::InputLocation::Pos(p) => p,
        pest::error::InputLocation::Span((s, _)) => s,
    };
    // A bracket left open joins the following lines into one: point at it.
    if let Some(open) = super::lexer::unclosed_bracket(text, offset) {
        let (l, c) = super::lexer::line_col(src, offset);
        let (lo, _) = super::lexer::line_col(src, open);
        // A file cut in the middle of a call ends inside the bracket, maybe on the bracket's own line.
        let at_end = text[offset.min(text.len())..].trim().is_empty();
        if at_end {
            let ch = &text[open..open + 1];
            return SyntaxError {
                offset: open,
                message: format!("invalid syntax: '{ch}' is never closed (the file ends at line {l}, column {c})"),
            };
        }
        if l > lo {
            let ch = &text[open..open + 1];
            return SyntaxError {
                offset: open,
                message: format!("invalid syntax: '{ch}' is never closed (the error shows at line {l}, column {c})"),
            };
        }
    }
    let message = describe(text, offset, &e.variant);
    SyntaxError { offset, message }
}

fn describe(text: &str, offset: usize, v: &pest::error::ErrorVariant<Rule>) -> String {
    let rest = &text[offset.min(text.len())..];
    let next = rest.chars().next();
    // Brackets left open swallow the rest of the file into one logical line.
    let mut depth = 0i32;
    for c in text[..offset.min(text.len())].chars() {
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            _ => {}
        }
    }
    let found = match next {
        None => "end of file".to_string(),
        Some('\n') | Some('\r') => "end of line".to_string(),
        Some(c) if c.is_whitespace() && rest.trim_start().is_empty() => "end of file".to_string(),
        Some(_) => {
            let tok: String = rest.chars().take_while(|c| !c.is_whitespace()).take(20).collect();
            format!("'{tok}'")
        }
    };
    if let pest::error::ErrorVariant::ParsingError { positives, .. } = v {
        let indent_problem = positives.is_empty()
            || (text[..offset.min(text.len())].ends_with('\n') || offset == 0) && rest.starts_with([' ', '\t']);
        if indent_problem && rest.starts_with([' ', '\t']) {
            return "invalid syntax: unexpected indent".to_string();
        }
    }
    if depth > 0 && next.is_none() {
        return "invalid syntax: unclosed bracket".to_string();
    }
    format!("invalid syntax: unexpected {found}")
}

// ------------------------------------------------------------------ helpers

fn span(p: &Pair<Rule>) -> Span {
    let s = p.as_span();
    Span { start: s.start(), end: s.end() }
}

fn ident(p: Pair<Rule>) -> String {
    p.as_str().to_string()
}

// ------------------------------------------------------------------ statements

fn stmt(p: Pair<Rule>, out: &mut Vec<Stmt>) -> PResult<()> {
    match p.as_rule() {
        Rule::simple_line => {
            let stmts = p.into_inner().next().unwrap();
            for s in stmts.into_inner() {
                out.push(small_stmt(s)?);
            }
        }
        Rule::if_stmt => out.push(if_stmt(p)?),
        Rule::for_stmt => out.push(for_stmt(p)?),
        Rule::while_stmt => out.push(while_stmt(p)?),
        Rule::try_stmt => out.push(try_stmt(p)?),
        Rule::def_stmt => out.push(def_stmt(p)?),
        Rule::with_stmt => out.push(with_stmt(p)?),
        Rule::class_stmt => out.push(class_stmt(p)?),
        Rule::decorated => out.push(decorated(p)?),
        r => unreachable!("statement rule {r:?}"),
    }
    Ok(())
}

fn suite(p: Pair<Rule>) -> PResult<Vec<Stmt>> {
    let mut out = Vec::new();
    for c in p.into_inner() {
        match c.as_rule() {
            Rule::indented => {
                for s in c.into_inner() {
                    stmt(s, &mut out)?;
                }
            }
            _ => stmt(c, &mut out)?,
        }
    }
    Ok(out)
}

fn else_suite(p: Pair<Rule>) -> PResult<Vec<Stmt>> {
    let mut inner = p.into_inner();
    inner.next(); // kw_else
    suite(inner.next().unwrap())
}

fn if_stmt(p: Pair<Rule>) -> PResult<Stmt> {
    let sp = span(&p);
    let mut branches = Vec::new();
    let mut orelse = Vec::new();
    let mut inner = p.into_inner();
    inner.next(); // kw_if
    let cond = test(inner.next().unwrap().into_inner().next().unwrap())?;
    branches.push((cond, suite(inner.next().unwrap())?));
    for c in inner {
        match c.as_rule() {
            Rule::elif_clause => {
                let mut ci = c.into_inner();
                ci.next();
                let cond = test(ci.next().unwrap().into_inner().next().unwrap())?;
                branches.push((cond, suite(ci.next().unwrap())?));
            }
            Rule::else_clause => orelse = else_suite(c)?,
            r => unreachable!("{r:?}"),
        }
    }
    Ok(Stmt { kind: StmtKind::If { branches, orelse }, span: sp })
}

fn for_stmt(p: Pair<Rule>) -> PResult<Stmt> {
    let sp = span(&p);
    let mut inner = p.into_inner();
    inner.next(); // kw_for
    let target = target_list(inner.next().unwrap().into_inner().next().unwrap())?;
    inner.next(); // kw_in
    let iter = testlist(inner.next().unwrap().into_inner().next().unwrap())?;
    let body = suite(inner.next().unwrap())?;
    let orelse = match inner.next() {
        Some(e) => else_suite(e)?,
        None => Vec::new(),
    };
    Ok(Stmt { kind: StmtKind::For { target, iter, body, orelse }, span: sp })
}

fn while_stmt(p: Pair<Rule>) -> PResult<Stmt> {
    let sp = span(&p);
    let mut inner = p.into_inner();
    inner.next();
    let cond = test(inner.next().unwrap().into_inner().next().unwrap())?;
    let body = suite(inner.next().unwrap())?;
    let orelse = match inner.next() {
        Some(e) => else_suite(e)?,
        None => Vec::new(),
    };
    Ok(Stmt { kind: StmtKind::While { cond, body, orelse }, span: sp })
}

fn try_stmt(p: Pair<Rule>) -> PResult<Stmt> {
    let sp = span(&p);
    let mut inner = p.into_inner();
    inner.next(); // kw_try
    let body = suite(inner.next().unwrap())?;
    let (mut handlers, mut orelse, mut finalbody) = (Vec::new(), Vec::new(), Vec::new());
    for c in inner {
        match c.as_rule() {
            Rule::except_clause => {
                let hsp = span(&c);
                let (mut types, mut name, mut body) = (None, None, Vec::new());
                for part in c.into_inner() {
                    match part.as_rule() {
                        Rule::kw_except | Rule::kw_as => {}
                        Rule::except_types => types = Some(test(part.into_inner().next().unwrap())?),
                        Rule::ident => name = Some(ident(part)),
                        Rule::suite => body = suite(part)?,
                        r => unreachable!("except clause rule {r:?}"),
                    }
                }
                handlers.push(Handler { types, name, body, span: hsp });
            }
            Rule::else_clause => orelse = else_suite(c)?,
            Rule::finally_clause => {
                let mut fi = c.into_inner();
                fi.next(); // kw_finally
                finalbody = suite(fi.next().unwrap())?;
            }
            r => unreachable!("try statement rule {r:?}"),
        }
    }
    Ok(Stmt { kind: StmtKind::Try { body, handlers, orelse, finalbody }, span: sp })
}

fn params(p: Pair<Rule>) -> PResult<Vec<Param>> {
    let mut out = Vec::new();
    for prm in p.into_inner() {
        let mut pi = prm.into_inner();
        let first = pi.next().unwrap();
        match first.as_rule() {
            Rule::star_param => out.push(Param::Star(ident(first.into_inner().next().unwrap()))),
            Rule::dstar_param => out.push(Param::DoubleStar(ident(first.into_inner().next().unwrap()))),
            Rule::ident => {
                let default = match pi.next() {
                    Some(d) => Some(test(d)?),
                    None => None,
                };
                out.push(Param::Plain(ident(first), default));
            }
            r => unreachable!("{r:?}"),
        }
    }
    Ok(out)
}

fn def_stmt(p: Pair<Rule>) -> PResult<Stmt> {
    let sp = span(&p);
    let mut inner = p.into_inner();
    inner.next(); // kw_def
    let name = ident(inner.next().unwrap());
    let mut prms = Vec::new();
    let mut body = Vec::new();
    for c in inner {
        match c.as_rule() {
            Rule::params_x => prms = params(c.into_inner().next().unwrap())?,
            Rule::suite => body = suite(c)?,
            r => unreachable!("{r:?}"),
        }
    }
    let def = Rc::new(FuncDef { name, params: prms, body, span: sp });
    Ok(Stmt { kind: StmtKind::Def(def), span: sp })
}

fn with_stmt(p: Pair<Rule>) -> PResult<Stmt> {
    let sp = span(&p);
    let mut inner = p.into_inner();
    inner.next(); // kw_with
    let mut items = Vec::new();
    for it in inner.next().unwrap().into_inner() {
        let mut parts = it.into_inner();
        let ctx = test(parts.next().unwrap())?;
        let target = match parts.nth(1) {
            Some(t) => Some(assignable(target(t)?)?),
            None => None,
        };
        items.push((ctx, target));
    }
    let body = suite(inner.next().unwrap())?;
    Ok(Stmt { kind: StmtKind::With { items, body }, span: sp })
}

fn class_stmt(p: Pair<Rule>) -> PResult<Stmt> {
    let sp = span(&p);
    let mut inner = p.into_inner();
    inner.next(); // kw_class
    let name = ident(inner.next().unwrap());
    let mut bases = Vec::new();
    let mut body = Vec::new();
    for c in inner {
        match c.as_rule() {
            Rule::bases_x => {
                for a in arglist(c.into_inner().next().unwrap())? {
                    match a {
                        Arg::Positional(e) => bases.push(e),
                        _ => return err(sp.start, "class keywords (metaclass=...) are not supported"),
                    }
                }
            }
            Rule::suite => body = suite(c)?,
            r => unreachable!("{r:?}"),
        }
    }
    Ok(Stmt { kind: StmtKind::Class(Rc::new(ClassDef { name, bases, body, span: sp })), span: sp })
}

fn decorated(p: Pair<Rule>) -> PResult<Stmt> {
    let sp = span(&p);
    let mut decorators = Vec::new();
    let mut def = None;
    for c in p.into_inner() {
        match c.as_rule() {
            Rule::decorator => decorators.push(test(c.into_inner().next().unwrap().into_inner().next().unwrap())?),
            Rule::def_stmt => def = Some(def_stmt(c)?),
            Rule::class_stmt => def = Some(class_stmt(c)?),
            r => unreachable!("{r:?}"),
        }
    }
    Ok(Stmt { kind: StmtKind::Decorated { decorators, def: Box::new(def.unwrap()) }, span: sp })
}

fn small_stmt(p: Pair<Rule>) -> PResult<Stmt> {
    let sp = span(&p);
    let kind = match p.as_rule() {
        Rule::pass_stmt => StmtKind::Pass,
        Rule::break_stmt => StmtKind::Break,
        Rule::continue_stmt => StmtKind::Continue,
        Rule::return_stmt => {
            let mut inner = p.into_inner();
            inner.next();
            StmtKind::Return(match inner.next() {
                Some(t) => Some(testlist(t)?),
                None => None,
            })
        }
        Rule::del_stmt => {
            let mut inner = p.into_inner();
            inner.next();
            let t = target_list(inner.next().unwrap())?;
            match t.kind {
                ExprKind::Tuple(items) => StmtKind::Del(items),
                _ => StmtKind::Del(vec![t]),
            }
        }
        Rule::global_stmt => StmtKind::Global(p.into_inner().skip(1).map(ident).collect()),
        Rule::assert_stmt => {
            let mut inner = p.into_inner().skip(1);
            let c = test(inner.next().unwrap())?;
            let m = match inner.next() {
                Some(m) => Some(test(m)?),
                None => None,
            };
            StmtKind::Assert(c, m)
        }
        Rule::raise_stmt => {
            let mut inner = p.into_inner().skip(1);
            StmtKind::Raise(match inner.next() {
                Some(t) => Some(test(t)?),
                None => None,
            })
        }
        Rule::import_stmt => {
            let mut names = Vec::new();
            for d in p.into_inner().skip(1) {
                let mut di = d.into_inner();
                let module = di.next().unwrap().as_str().to_string();
                let alias = di.nth(1).map(ident);
                names.push((module, alias));
            }
            StmtKind::Import(names)
        }
        Rule::from_import => {
            let mut inner = p.into_inner();
            inner.next(); // from
            let module = inner.next().unwrap().as_str().to_string();
            inner.next(); // import
            let what = inner.next().unwrap();
            let names = match what.as_rule() {
                Rule::import_star => None,
                _ => Some(
                    what.into_inner()
                        .map(|ia| {
                            let mut ii = ia.into_inner();
                            let n = ident(ii.next().unwrap());
                            let a = ii.nth(1).map(ident);
                            (n, a)
                        })
                        .collect(),
                ),
            };
            StmtKind::FromImport { module, names }
        }
        Rule::expr_stmt => expr_stmt(p)?,
        r => unreachable!("small statement {r:?}"),
    };
    Ok(Stmt { kind, span: sp })
}

fn expr_stmt(p: Pair<Rule>) -> PResult<StmtKind> {
    let parts: Vec<Pair<Rule>> = p.into_inner().collect();
    if parts.len() == 1 {
        return Ok(StmtKind::Expr(testlist(parts.into_iter().next().unwrap())?));
    }
    if parts[1].as_rule() == Rule::augop {
        let mut it = parts.into_iter();
        let target = assignable(testlist(it.next().unwrap())?)?;
        let op = match it.next().unwrap().as_str() {
            "+=" => BinOp::Add,
            "-=" => BinOp::Sub,
            "*=" => BinOp::Mul,
            "/=" => BinOp::Div,
            "//=" => BinOp::FloorDiv,
            "%=" => BinOp::Mod,
            "**=" => BinOp::Pow,
            "|=" => BinOp::BitOr,
            "&=" => BinOp::BitAnd,
            "^=" => BinOp::BitXor,
            "<<=" => BinOp::LShift,
            ">>=" => BinOp::RShift,
            o => unreachable!("{o}"),
        };
        if matches!(target.kind, ExprKind::Tuple(_) | ExprKind::List(_)) {
            return err(target.span.start, "invalid syntax: illegal expression for augmented assignment");
        }
        let value = testlist(it.next().unwrap())?;
        return Ok(StmtKind::AugAssign { target, op, value });
    }
    let mut exprs = Vec::new();
    for part in parts {
        if part.as_rule() == Rule::testlist {
            exprs.push(testlist(part)?);
        }
    }
    let value = exprs.pop().unwrap();
    let targets = exprs.into_iter().map(assignable).collect::<PResult<Vec<_>>>()?;
    Ok(StmtKind::Assign { targets, value })
}

/// Check that an expression parsed on the left of `=` can be assigned to.
fn assignable(e: Expr) -> PResult<Expr> {
    match e.kind {
        ExprKind::Name(_) | ExprKind::Subscript(..) | ExprKind::Attr(..) => Ok(e),
        ExprKind::Tuple(items) | ExprKind::List(items) => {
            let items = items.into_iter().map(assignable).collect::<PResult<Vec<_>>>()?;
            Ok(Expr::new(ExprKind::Tuple(items), e.span))
        }
        ExprKind::Call(..) => err(e.span.start, "invalid syntax: cannot assign to function call"),
        ExprKind::Int(_) | ExprKind::Float(_) | ExprKind::Str(_) | ExprKind::None | ExprKind::Bool(_) => {
            err(e.span.start, "invalid syntax: cannot assign to literal")
        }
        _ => err(e.span.start, "invalid syntax: cannot assign to expression"),
    }
}

fn has_trailing_comma(p: &Pair<Rule>) -> bool {
    p.as_str().trim_end().ends_with(',')
}

fn target_list(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let tuple = has_trailing_comma(&p);
    let mut items = Vec::new();
    for t in p.into_inner() {
        items.push(target(t)?);
    }
    if items.len() == 1 && !tuple {
        Ok(items.pop().unwrap())
    } else {
        Ok(Expr::new(ExprKind::Tuple(items), sp))
    }
}

fn target(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let inner = p.into_inner().next().unwrap();
    let e = match inner.as_rule() {
        Rule::target_list => target_list(inner)?,
        Rule::postfix => postfix(inner)?,
        r => unreachable!("{r:?}"),
    };
    match &e.kind {
        ExprKind::Name(_) | ExprKind::Subscript(..) | ExprKind::Attr(..) | ExprKind::Tuple(_) => Ok(e),
        _ => err(sp.start, "invalid syntax: cannot assign to expression"),
    }
}

// ------------------------------------------------------------------ expressions

fn testlist(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let tuple = has_trailing_comma(&p);
    let mut items = Vec::new();
    for t in p.into_inner() {
        items.push(test(t)?);
    }
    if items.len() == 1 && !tuple {
        Ok(items.pop().unwrap())
    } else {
        Ok(Expr::new(ExprKind::Tuple(items), sp))
    }
}

fn test(p: Pair<Rule>) -> PResult<Expr> {
    debug_assert_eq!(p.as_rule(), Rule::test);
    let inner = p.into_inner().next().unwrap();
    match inner.as_rule() {
        Rule::lambda => lambda(inner),
        Rule::ternary => ternary(inner),
        r => unreachable!("{r:?}"),
    }
}

fn lambda(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let mut prms = Vec::new();
    let mut body = None;
    for c in p.into_inner() {
        match c.as_rule() {
            Rule::kw_lambda => {}
            Rule::params => prms = params(c)?,
            Rule::test => body = Some(test(c)?),
            r => unreachable!("{r:?}"),
        }
    }
    let body = body.unwrap();
    let bsp = body.span;
    let def = FuncDef {
        name: "<lambda>".into(),
        params: prms,
        body: vec![Stmt { kind: StmtKind::Return(Some(body)), span: bsp }],
        span: sp,
    };
    Ok(Expr::new(ExprKind::Lambda(Rc::new(def)), sp))
}

fn ternary(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let mut inner = p.into_inner();
    let first = or_test(inner.next().unwrap())?;
    if inner.next().is_none() {
        return Ok(first);
    }
    let cond = or_test(inner.next().unwrap())?;
    inner.next(); // else
    let orelse = test(inner.next().unwrap())?;
    Ok(Expr::new(ExprKind::IfExp { cond: Box::new(cond), then: Box::new(first), orelse: Box::new(orelse) }, sp))
}

fn or_test(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let mut inner = p.into_inner().filter(|c| c.as_rule() != Rule::kw_or);
    let mut acc = and_test(inner.next().unwrap())?;
    for c in inner {
        let r = and_test(c)?;
        acc = Expr::new(ExprKind::Or(Box::new(acc), Box::new(r)), sp);
    }
    Ok(acc)
}

fn and_test(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let mut inner = p.into_inner().filter(|c| c.as_rule() != Rule::kw_and);
    let mut acc = not_test(inner.next().unwrap())?;
    for c in inner {
        let r = not_test(c)?;
        acc = Expr::new(ExprKind::And(Box::new(acc), Box::new(r)), sp);
    }
    Ok(acc)
}

fn not_test(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let inner = p.into_inner().next().unwrap();
    match inner.as_rule() {
        Rule::not_op => {
            let operand = not_test(inner.into_inner().nth(1).unwrap())?;
            Ok(Expr::new(ExprKind::Unary(UnOp::Not, Box::new(operand)), sp))
        }
        Rule::comparison => comparison(inner),
        r => unreachable!("{r:?}"),
    }
}

fn comparison(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let mut inner = p.into_inner();
    let first = bor(inner.next().unwrap())?;
    let mut rest = Vec::new();
    while let Some(op) = inner.next() {
        let o = match op.as_str() {
            "==" => CmpOp::Eq,
            "!=" => CmpOp::Ne,
            "<" => CmpOp::Lt,
            "<=" => CmpOp::Le,
            ">" => CmpOp::Gt,
            ">=" => CmpOp::Ge,
            "in" => CmpOp::In,
            "is" => CmpOp::Is,
            s if s.starts_with("not") => CmpOp::NotIn,
            _ => CmpOp::IsNot,
        };
        rest.push((o, bor(inner.next().unwrap())?));
    }
    if rest.is_empty() {
        Ok(first)
    } else {
        Ok(Expr::new(ExprKind::Compare(Box::new(first), rest), sp))
    }
}

fn binop(s: &str) -> BinOp {
    // A bit operator's rule (`"|" ~ !"="`) spans the blanks before the look-ahead.
    match s.trim_end() {
        "+" => BinOp::Add,
        "-" => BinOp::Sub,
        "*" => BinOp::Mul,
        "/" => BinOp::Div,
        "//" => BinOp::FloorDiv,
        "%" => BinOp::Mod,
        "|" => BinOp::BitOr,
        "^" => BinOp::BitXor,
        "&" => BinOp::BitAnd,
        "<<" => BinOp::LShift,
        ">>" => BinOp::RShift,
        _ => BinOp::Pow,
    }
}

/// A left-associative level of binary operators over the operands `next` parses.
fn left_assoc(p: Pair<Rule>, next: fn(Pair<Rule>) -> PResult<Expr>) -> PResult<Expr> {
    let mut inner = p.into_inner();
    let mut acc = next(inner.next().unwrap())?;
    while let Some(op) = inner.next() {
        let r = next(inner.next().unwrap())?;
        let sp = Span { start: acc.span.start, end: r.span.end };
        acc = Expr::new(ExprKind::BinOp(Box::new(acc), binop(op.as_str()), Box::new(r)), sp);
    }
    Ok(acc)
}

fn bor(p: Pair<Rule>) -> PResult<Expr> {
    left_assoc(p, bxor)
}

fn bxor(p: Pair<Rule>) -> PResult<Expr> {
    left_assoc(p, band)
}

fn band(p: Pair<Rule>) -> PResult<Expr> {
    left_assoc(p, shift)
}

fn shift(p: Pair<Rule>) -> PResult<Expr> {
    left_assoc(p, arith)
}

fn arith(p: Pair<Rule>) -> PResult<Expr> {
    let mut inner = p.into_inner();
    let mut acc = term(inner.next().unwrap())?;
    while let Some(op) = inner.next() {
        let r = term(inner.next().unwrap())?;
        let sp = Span { start: acc.span.start, end: r.span.end };
        acc = Expr::new(ExprKind::BinOp(Box::new(acc), binop(op.as_str()), Box::new(r)), sp);
    }
    Ok(acc)
}

fn term(p: Pair<Rule>) -> PResult<Expr> {
    let mut inner = p.into_inner();
    let mut acc = factor(inner.next().unwrap())?;
    while let Some(op) = inner.next() {
        let r = factor(inner.next().unwrap())?;
        let sp = Span { start: acc.span.start, end: r.span.end };
        acc = Expr::new(ExprKind::BinOp(Box::new(acc), binop(op.as_str()), Box::new(r)), sp);
    }
    Ok(acc)
}

fn factor(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let mut inner = p.into_inner();
    let first = inner.next().unwrap();
    match first.as_rule() {
        Rule::unary_op => {
            let operand = factor(inner.next().unwrap())?;
            let op = match first.as_str() {
                "-" => UnOp::Neg,
                "+" => UnOp::Pos,
                _ => UnOp::Invert,
            };
            // Fold negative literals so that -5 is an Int constant.
            match (&operand.kind, op) {
                (ExprKind::Int(i), UnOp::Neg) => Ok(Expr::new(ExprKind::Int(-i), sp)),
                (ExprKind::Float(f), UnOp::Neg) => Ok(Expr::new(ExprKind::Float(-f), sp)),
                _ => Ok(Expr::new(ExprKind::Unary(op, Box::new(operand)), sp)),
            }
        }
        Rule::power => power(first),
        r => unreachable!("{r:?}"),
    }
}

fn power(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let mut inner = p.into_inner();
    let base = postfix(inner.next().unwrap())?;
    match inner.next() {
        None => Ok(base),
        Some(e) => {
            let exp = factor(e)?;
            Ok(Expr::new(ExprKind::BinOp(Box::new(base), BinOp::Pow, Box::new(exp)), sp))
        }
    }
}

fn postfix(p: Pair<Rule>) -> PResult<Expr> {
    let mut inner = p.into_inner();
    let mut acc = atom(inner.next().unwrap())?;
    for tr in inner {
        let t = tr.into_inner().next().unwrap();
        let tsp = span(&t);
        let sp = Span { start: acc.span.start, end: tsp.end };
        acc = match t.as_rule() {
            Rule::call => {
                let args = match t.into_inner().next() {
                    Some(al) => arglist(al)?,
                    None => Vec::new(),
                };
                Expr::new(ExprKind::Call(Box::new(acc), args), sp)
            }
            Rule::subscript => {
                let sl = t.into_inner().next().unwrap();
                let tuple = has_trailing_comma(&sl);
                let slsp = span(&sl);
                let mut items = Vec::new();
                for it in sl.into_inner() {
                    items.push(subscript_item(it)?);
                }
                let index = if items.len() == 1 && !tuple {
                    items.pop().unwrap()
                } else {
                    Expr::new(ExprKind::Tuple(items), slsp)
                };
                Expr::new(ExprKind::Subscript(Box::new(acc), Box::new(index)), sp)
            }
            Rule::attribute => {
                let name = ident(t.into_inner().next().unwrap());
                Expr::new(ExprKind::Attr(Box::new(acc), name), sp)
            }
            r => unreachable!("{r:?}"),
        };
    }
    Ok(acc)
}

fn subscript_item(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let children: Vec<Pair<Rule>> = p.into_inner().collect();
    if children.len() == 1 && children[0].as_rule() == Rule::test {
        return test(children.into_iter().next().unwrap());
    }
    // A slice: tests fill the slots between colons.
    let mut parts: [Option<Box<Expr>>; 3] = [None, None, None];
    let mut slot = 0;
    for c in children {
        match c.as_rule() {
            Rule::colon => slot += 1,
            _ => parts[slot.min(2)] = Some(Box::new(test(c)?)),
        }
    }
    let [a, b, c] = parts;
    Ok(Expr::new(ExprKind::Slice(a, b, c), sp))
}

fn arglist(p: Pair<Rule>) -> PResult<Vec<Arg>> {
    let mut out = Vec::new();
    let mut seen_kw = false;
    for a in p.into_inner() {
        let asp = span(&a);
        let mut ai = a.into_inner();
        let first = ai.next().unwrap();
        match first.as_rule() {
            Rule::kwarg => {
                seen_kw = true;
                let ksp = span(&first);
                let mut ki = first.into_inner();
                let name = ident(ki.next().unwrap());
                out.push(Arg::Keyword(name, test(ki.next().unwrap())?, ksp));
            }
            Rule::star_arg => out.push(Arg::Star(test(first.into_inner().next().unwrap())?)),
            Rule::dstar_arg => {
                seen_kw = true;
                out.push(Arg::DoubleStar(test(first.into_inner().next().unwrap())?))
            }
            Rule::test => {
                if seen_kw {
                    return err(asp.start, "invalid syntax: positional argument follows keyword argument");
                }
                let e = test(first)?;
                match ai.next() {
                    Some(cf) => {
                        let comps = comp_for(cf)?;
                        out.push(Arg::Positional(Expr::new(ExprKind::GenExp(Box::new(e), comps), asp)))
                    }
                    None => out.push(Arg::Positional(e)),
                }
            }
            r => unreachable!("{r:?}"),
        }
    }
    Ok(out)
}

fn comp_for(p: Pair<Rule>) -> PResult<Vec<Comprehension>> {
    let mut out = Vec::new();
    let mut cur = Some(p);
    while let Some(c) = cur.take() {
        match c.as_rule() {
            Rule::comp_for => {
                let mut ci = c.into_inner();
                ci.next(); // for
                let target = target_list(ci.next().unwrap())?;
                ci.next(); // in
                let iter = or_test(ci.next().unwrap())?;
                out.push(Comprehension { target, iter, conds: Vec::new() });
                cur = ci.next();
            }
            Rule::comp_if => {
                let mut ci = c.into_inner();
                ci.next(); // if
                let cond = or_test(ci.next().unwrap())?;
                out.last_mut().unwrap().conds.push(cond);
                cur = ci.next();
            }
            r => unreachable!("{r:?}"),
        }
    }
    Ok(out)
}

fn atom(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let inner = p.into_inner().next().unwrap();
    let kind = match inner.as_rule() {
        Rule::number => return number(inner),
        Rule::strings => return strings(inner),
        Rule::kw_none => ExprKind::None,
        Rule::kw_true => ExprKind::Bool(true),
        Rule::kw_false => ExprKind::Bool(false),
        Rule::ident => ExprKind::Name(ident(inner)),
        Rule::paren => match inner.into_inner().next() {
            None => ExprKind::Tuple(Vec::new()),
            Some(body) => {
                let (first, rest) = seq_body(body)?;
                match rest {
                    SeqRest::Comp(c) => ExprKind::GenExp(Box::new(first), c),
                    SeqRest::Items(items, false) if items.is_empty() => {
                        // A parenthesized expression: keep its own kind, with the parens' span.
                        let mut e = first;
                        e.span = sp;
                        return Ok(e);
                    }
                    SeqRest::Items(mut items, _) => {
                        items.insert(0, first);
                        ExprKind::Tuple(items)
                    }
                }
            }
        },
        Rule::list_display => match inner.into_inner().next() {
            None => ExprKind::List(Vec::new()),
            Some(body) => {
                let (first, rest) = seq_body(body)?;
                match rest {
                    SeqRest::Comp(c) => ExprKind::ListComp(Box::new(first), c),
                    SeqRest::Items(mut items, _) => {
                        items.insert(0, first);
                        ExprKind::List(items)
                    }
                }
            }
        },
        Rule::dict_display => match inner.into_inner().next() {
            None => ExprKind::Dict(Vec::new()),
            Some(body) => {
                let mut bi = body.into_inner();
                let (k, v) = dict_item(bi.next().unwrap())?;
                let rest = bi.next().unwrap();
                match rest.as_rule() {
                    Rule::comp_for => ExprKind::DictComp(Box::new(k), Box::new(v), comp_for(rest)?),
                    _ => {
                        let mut items = vec![(k, v)];
                        for it in rest.into_inner() {
                            items.push(dict_item(it)?);
                        }
                        ExprKind::Dict(items)
                    }
                }
            }
        },
        r => unreachable!("{r:?}"),
    };
    Ok(Expr::new(kind, sp))
}

enum SeqRest {
    Comp(Vec<Comprehension>),
    /// More items; true when a comma was written (so `(x,)` is a tuple).
    Items(Vec<Expr>, bool),
}

fn seq_body(p: Pair<Rule>) -> PResult<(Expr, SeqRest)> {
    let mut it = p.into_inner();
    let first = test(it.next().unwrap())?;
    let rest = it.next().unwrap();
    Ok(match rest.as_rule() {
        Rule::comp_for => (first, SeqRest::Comp(comp_for(rest)?)),
        _ => {
            let comma = rest.as_str().contains(',');
            let items = rest.into_inner().map(test).collect::<PResult<Vec<_>>>()?;
            (first, SeqRest::Items(items, comma))
        }
    })
}

fn dict_item(p: Pair<Rule>) -> PResult<(Expr, Expr)> {
    let mut i = p.into_inner();
    Ok((test(i.next().unwrap())?, test(i.next().unwrap())?))
}

fn number(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let inner = p.into_inner().next().unwrap();
    let text: String = inner.as_str().chars().filter(|c| *c != '_').collect();
    let kind = match inner.as_rule() {
        Rule::float => match text.parse::<f64>() {
            Ok(v) => ExprKind::Float(v),
            Err(_) => return err(sp.start, format!("invalid number literal '{text}'")),
        },
        Rule::imag => {
            let t = &text[..text.len() - 1];
            ExprKind::Imag(t.parse::<f64>().unwrap_or(0.0))
        }
        Rule::int => {
            let lower = text.to_ascii_lowercase();
            let parsed = if let Some(h) = lower.strip_prefix("0x") {
                i64::from_str_radix(h, 16)
            } else if let Some(o) = lower.strip_prefix("0o") {
                i64::from_str_radix(o, 8)
            } else if let Some(b) = lower.strip_prefix("0b") {
                i64::from_str_radix(b, 2)
            } else {
                if lower.len() > 1 && lower.starts_with('0') && lower.chars().any(|c| c != '0') {
                    return err(
                        sp.start,
                        "invalid syntax: leading zeros in decimal integer literals are not permitted",
                    );
                }
                lower.parse::<i64>()
            };
            match parsed {
                Ok(v) => ExprKind::Int(v),
                Err(_) => return err(sp.start, format!("integer literal '{text}' is out of range")),
            }
        }
        r => unreachable!("{r:?}"),
    };
    Ok(Expr::new(kind, sp))
}

fn strings(p: Pair<Rule>) -> PResult<Expr> {
    let sp = span(&p);
    let mut parts: Vec<FPart> = Vec::new();
    let mut any_f = false;
    for s in p.into_inner() {
        let ssp = span(&s);
        let mut prefix = String::new();
        let mut body = None;
        for c in s.into_inner() {
            match c.as_rule() {
                Rule::str_prefix => prefix = c.as_str().to_ascii_lowercase(),
                _ => body = Some(c),
            }
        }
        let body = body.unwrap();
        let raw_text = body.as_str();
        let q = if matches!(body.as_rule(), Rule::long_dq | Rule::long_sq) { 3 } else { 1 };
        let content = &raw_text[q..raw_text.len() - q];
        let content_off = span(&body).start + q;
        let raw = prefix.contains('r');
        if prefix.contains('f') {
            any_f = true;
            let mut fparts = fstring(content, content_off, raw)?;
            parts.append(&mut fparts);
        } else {
            let text = if raw { content.to_string() } else { unescape(content, ssp.start)? };
            parts.push(FPart::Lit(text));
        }
    }
    if !any_f {
        let mut s = String::new();
        for p in parts {
            if let FPart::Lit(t) = p {
                s.push_str(&t);
            }
        }
        return Ok(Expr::new(ExprKind::Str(s), sp));
    }
    Ok(Expr::new(ExprKind::FString(parts), sp))
}

fn unescape(s: &str, at: usize) -> PResult<String> {
    let mut out = String::with_capacity(s.len());
    let mut chars = s.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        match chars.next() {
            Some('n') => out.push('\n'),
            Some('t') => out.push('\t'),
            Some('r') => out.push('\r'),
            Some('0') => out.push('\0'),
            Some('\\') => out.push('\\'),
            Some('\'') => out.push('\''),
            Some('"') => out.push('"'),
            Some('a') => out.push('\x07'),
            Some('b') => out.push('\x08'),
            Some('f') => out.push('\x0C'),
            Some('v') => out.push('\x0B'),
            Some('\n') => {}
            Some('x') => {
                let h: String = chars.by_ref().take(2).collect();
                match u32::from_str_radix(&h, 16).ok().and_then(char::from_u32) {
                    Some(ch) => out.push(ch),
                    None => return err(at, format!("invalid \\x escape '\\x{h}'")),
                }
            }
            Some('u') => {
                let h: String = chars.by_ref().take(4).collect();
                match u32::from_str_radix(&h, 16).ok().and_then(char::from_u32) {
                    Some(ch) => out.push(ch),
                    None => return err(at, format!("invalid \\u escape '\\u{h}'")),
                }
            }
            Some(o) => {
                out.push('\\');
                out.push(o);
            }
            None => out.push('\\'),
        }
    }
    Ok(out)
}

/// Split f-string content into literal text and replacement fields.
fn fstring(content: &str, off: usize, raw: bool) -> PResult<Vec<FPart>> {
    let mut parts = Vec::new();
    let mut lit = String::new();
    let b: Vec<(usize, char)> = content.char_indices().collect();
    let mut i = 0;
    let flush = |lit: &mut String, parts: &mut Vec<FPart>| -> PResult<()> {
        if !lit.is_empty() {
            let t = if raw { lit.clone() } else { unescape(lit, off)? };
            parts.push(FPart::Lit(t));
            lit.clear();
        }
        Ok(())
    };
    while i < b.len() {
        let (pos, c) = b[i];
        if c == '{' && i + 1 < b.len() && b[i + 1].1 == '{' {
            lit.push('{');
            i += 2;
            continue;
        }
        if c == '}' && i + 1 < b.len() && b[i + 1].1 == '}' {
            lit.push('}');
            i += 2;
            continue;
        }
        if c == '}' {
            return err(off + pos, "f-string: single '}' is not allowed");
        }
        if c != '{' {
            lit.push(c);
            i += 1;
            continue;
        }
        flush(&mut lit, &mut parts)?;
        // Find the end of the field, honouring nested brackets and strings.
        let start = i + 1;
        let mut depth = 0;
        let mut j = start;
        let mut conv_at = None;
        let mut spec_at = None;
        let mut quote: Option<char> = None;
        while j < b.len() {
            let ch = b[j].1;
            if let Some(q) = quote {
                if ch == q {
                    quote = None;
                }
            } else if ch == '\'' || ch == '"' {
                quote = Some(ch);
            } else if ch == '(' || ch == '[' || ch == '{' {
                depth += 1;
            } else if (ch == ')' || ch == ']' || ch == '}') && depth > 0 {
                depth -= 1;
            } else if depth == 0 && ch == '}' {
                break;
            } else if depth == 0 && ch == '!' && spec_at.is_none() && b.get(j + 1).map(|x| x.1) != Some('=') {
                conv_at = Some(j);
            } else if depth == 0 && ch == ':' && spec_at.is_none() {
                spec_at = Some(j);
                // The spec runs to the matching close brace.
                let mut k = j + 1;
                let mut d = 0;
                while k < b.len() {
                    match b[k].1 {
                        '{' => d += 1,
                        '}' if d > 0 => d -= 1,
                        '}' => break,
                        _ => {}
                    }
                    k += 1;
                }
                j = k;
                break;
            }
            j += 1;
        }
        if j >= b.len() {
            return err(off + pos, "f-string: expecting '}'");
        }
        let byte = |idx: usize| {
            if idx < b.len() {
                b[idx].0
            } else {
                content.len()
            }
        };
        let expr_end = conv_at.or(spec_at).unwrap_or(j);
        let expr_text = &content[byte(start)..byte(expr_end)];
        if expr_text.trim().is_empty() {
            return err(off + pos, "f-string: empty expression not allowed");
        }
        let expr = parse_expr(expr_text, off + byte(start))?;
        let conv = match conv_at {
            None => None,
            Some(c) => match (b.get(c + 1).map(|x| x.1), c + 2 == spec_at.unwrap_or(j)) {
                (Some(k @ ('s' | 'r' | 'a')), true) => Some(k),
                (Some('s' | 'r' | 'a'), false) => return err(off + byte(c + 2), "f-string: expecting '}'"),
                _ => return err(off + byte(c), "f-string: invalid conversion character: expected 's', 'r', or 'a'"),
            },
        };
        let spec = match spec_at {
            Some(s) => fstring(&content[byte(s + 1)..byte(j)], off + byte(s + 1), raw)?,
            None => Vec::new(),
        };
        parts.push(FPart::Field { expr: Box::new(expr), conv, spec });
        i = j + 1;
    }
    flush(&mut lit, &mut parts)?;
    Ok(parts)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(src: &str) -> Module {
        parse_module(src).unwrap_or_else(|e| panic!("{src:?}: {e:?}"))
    }

    #[test]
    fn numeric_literals() {
        for (src, want) in [("5800E6", 5800e6), ("1.E-6", 1e-6), (".5", 0.5), ("1.", 1.0), ("2.5e+3", 2500.0)] {
            let m = parse(&format!("x = {src}\n"));
            match &m.body[0].kind {
                StmtKind::Assign { value: Expr { kind: ExprKind::Float(v), .. }, .. } => {
                    assert_eq!(*v, want, "{src}")
                }
                k => panic!("{src}: {k:?}"),
            }
        }
        let m = parse("x = 42\n");
        assert!(matches!(&m.body[0].kind, StmtKind::Assign { value: Expr { kind: ExprKind::Int(42), .. }, .. }));
    }

    #[test]
    fn blocks_and_indentation() {
        let m = parse("def f(x, y=2):\n    if x:\n        return 1\n    elif y:\n        pass\n    else:\n        return 3\n\n\nfor i in range(3):\n    a = i\nb = 1\n");
        assert_eq!(m.body.len(), 3);
        match &m.body[0].kind {
            StmtKind::Def(d) => {
                assert_eq!(d.params.len(), 2);
                match &d.body[0].kind {
                    StmtKind::If { branches, orelse } => {
                        assert_eq!(branches.len(), 2);
                        assert_eq!(orelse.len(), 1);
                    }
                    k => panic!("{k:?}"),
                }
            }
            k => panic!("{k:?}"),
        }
    }

    #[test]
    fn calls_with_continuations_and_comments() {
        let m = parse("A = CMD(X=1,  # comment\n        Y=_F(Z=(1, 2,),),\n        **kw)\nB = 1 + \\\n  2 ; C = 3\n");
        assert_eq!(m.body.len(), 3);
    }

    #[test]
    fn syntax_error_is_located() {
        let e = parse_module("A = 1\nB = (2,\nC = 3 +\n").unwrap_err();
        assert!(e.message.contains("invalid syntax"), "{e:?}");
        let e = parse_module("A = 1\n  B = 2\n").unwrap_err();
        assert_eq!(crate::syntax::lexer::line_col("A = 1\n  B = 2\n", e.offset).0, 2);
    }

    #[test]
    fn fstrings() {
        let m = parse("s = f'{a:>{w}} and {b!r}{{x}}'\n");
        match &m.body[0].kind {
            StmtKind::Assign { value: Expr { kind: ExprKind::FString(parts), .. }, .. } => {
                assert_eq!(parts.len(), 4)
            }
            k => panic!("{k:?}"),
        }
    }
}
