//! The modules a command file may import, and what Code_Aster's runner puts in its namespace.
//!
//! Code_Aster's runner (`run_aster/command_files.py`) starts a command file that does not import the
//! commands itself with `from math import *`, `import code_aster`, `from code_aster.Commands import *`
//! and `from code_aster import CA`: [`predefine`] does the same. The new-style preamble
//! (`from code_aster import CA`, `CA.init(...)`, `CA.close()`) is taken as DEBUT / FIN (the calls are
//! made by the interpreter, which knows its host). Of `os` and `os.path`, the functions that only
//! compute on their arguments are here; whatever reaches the file system or the process outside the
//! run's units is refused by name, as is the rest of the code_aster object API.

use super::value::{Builtin, Scope, Value};
use crate::concepts::{Concept, ConceptData, ConceptKind};
use crate::diag::{Error, Result};

/// The names Code_Aster's runner defines before a command file runs (when the file does not import
/// the commands itself, as its runner decides), `math`'s names apart (`interp::predefine` adds them):
/// false when the file imports the commands itself and gets nothing.
pub fn predefine(globals: &Scope, src: &str) -> bool {
    static IMPORTS: std::sync::OnceLock<regex::Regex> = std::sync::OnceLock::new();
    let re = IMPORTS.get_or_init(|| regex::Regex::new(r"(?m)^from +code_aster(\.Commands| +import +CA)").unwrap());
    let imports_itself = re.is_match(src);
    if imports_itself {
        return false;
    }
    let mut g = globals.borrow_mut();
    g.insert("code_aster".into(), Value::Module("code_aster"));
    g.insert("CA".into(), Value::Module("code_aster.CA"));
    g.insert("CO".into(), Value::Builtin(Builtin("CO")));
    true
}

/// `CO('name')`: the name of a concept a command is to create (CALC_MATR_ELEM's MATR_ELEM, ...).
pub fn co(args: &[Value]) -> Result<Value> {
    match args {
        [Value::Str(s)] if !s.is_empty() => {
            let c = Concept::new(ConceptKind::Co, ConceptData::Pending);
            c.set_name(s);
            Ok(Value::Concept(c))
        }
        _ => Err(Error::python("TypeError: CO() takes the name of the concept to create (a text)")),
    }
}

fn refused(what: &str, why: &str) -> Error {
    Error::unsupported(format!("{what}: {why} is not supported by aster-rs"))
}

const OS_PATH_PURE: &[&str] = &["join", "basename", "dirname", "splitext", "split", "normpath", "isabs"];
const OS_PATH_QUALIFIED: &[&str] = &[
    "os.path.join",
    "os.path.basename",
    "os.path.dirname",
    "os.path.splitext",
    "os.path.split",
    "os.path.normpath",
    "os.path.isabs",
];

/// The module object of an importable module path, or None.
pub fn module(path: &str) -> Option<Value> {
    Some(Value::Module(match path {
        "code_aster" => "code_aster",
        "code_aster.CA" => "code_aster.CA",
        "code_aster.Commands" => "code_aster.Commands",
        "os" => "os",
        "os.path" => "os.path",
        // Imported by files that never use them; every attribute stops by name.
        "sys" => "sys",
        "re" => "re",
        "numpy" => "numpy",
        "numpy.linalg" => "numpy.linalg",
        _ => return None,
    }))
}

/// `import a.b as c` binds c to a.b, `import a.b` binds a: the module to bind, or None when the
/// path is not one of ours.
pub fn import(path: &str, alias: bool) -> Option<Value> {
    module(path)?;
    if alias {
        module(path)
    } else {
        module(path.split('.').next().unwrap_or(path))
    }
}

/// `from MODULE import NAME`: the value, or None when MODULE is not one of ours.
pub fn from_import(module_path: &str, name: &str) -> Option<Result<Value>> {
    let m = module(module_path)?;
    if module_path.starts_with("numpy") {
        return Some(super::numpy::get_attr(module_path, name));
    }
    Some(get_attr(&m, name))
}

/// `from MODULE import *`.
pub fn star_import(module_path: &str) -> Option<Vec<(String, Value)>> {
    match module_path {
        // The commands are resolved through the host; CO comes with them.
        "code_aster.Commands" => Some(vec![("CO".into(), Value::Builtin(Builtin("CO")))]),
        "numpy" => Some(super::numpy::star()),
        "os.path" => Some(
            OS_PATH_PURE
                .iter()
                .zip(OS_PATH_QUALIFIED)
                .map(|(n, q)| (n.to_string(), Value::Builtin(Builtin(q))))
                .collect(),
        ),
        _ => None,
    }
}

/// An attribute of one of our modules.
pub fn get_attr(m: &Value, name: &str) -> Result<Value> {
    let Value::Module(path) = m else { unreachable!("get_attr on a module") };
    match (*path, name) {
        ("code_aster", "CA") => Ok(Value::Module("code_aster.CA")),
        ("code_aster", "Commands") => Ok(Value::Module("code_aster.Commands")),
        ("code_aster" | "code_aster.CA", "init") => Ok(Value::Builtin(Builtin("CA.init"))),
        ("code_aster" | "code_aster.CA", "close") => Ok(Value::Builtin(Builtin("CA.close"))),
        ("code_aster" | "code_aster.CA", "disable_fpe") => Ok(Value::Builtin(Builtin("CA.disable_fpe"))),
        ("code_aster.Commands", "CO") => Ok(Value::Builtin(Builtin("CO"))),
        ("code_aster" | "code_aster.CA", n) => Err(Error::unsupported(format!(
            "CA.{n}: the code_aster object API is not supported; use the commands only"
        ))),
        ("os", "path") => Ok(Value::Module("os.path")),
        ("os", "sep") | ("os.path", "sep") => Ok(Value::str("/")),
        ("os", "pathsep") => Ok(Value::str(":")),
        ("os", n) => {
            Err(refused(&format!("os.{n}"), "reaching the file system or the process outside the run's units"))
        }
        ("sys", n) => Err(refused(&format!("sys.{n}"), "the interpreter's process")),
        ("re", n) => Err(refused(&format!("re.{n}"), "the regular expressions module")),
        ("os.path", n) => match OS_PATH_PURE.iter().position(|p| *p == n) {
            Some(i) => Ok(Value::Builtin(Builtin(OS_PATH_QUALIFIED[i]))),
            None => Err(refused(&format!("os.path.{n}"), "reaching the file system outside the run's units")),
        },
        (p, n) => Err(Error::python(format!("AttributeError: module '{p}' has no attribute '{n}'"))),
    }
}

fn text_arg(f: &str, v: &Value) -> Result<String> {
    v.as_str()
        .map(str::to_string)
        .ok_or_else(|| Error::python(format!("TypeError: {f}() expects a text, got {}", v.type_name())))
}

/// Call `os.path.NAME` (the functions that compute on their arguments only), POSIX paths.
pub fn call_os_path(name: &str, args: &[Value]) -> Result<Value> {
    let one = || -> Result<String> {
        match args {
            [a] => text_arg(name, a),
            _ => Err(Error::python(format!("TypeError: {name}() takes exactly one argument ({} given)", args.len()))),
        }
    };
    let split = |p: &str| -> (String, String) {
        match p.rfind('/') {
            Some(i) => {
                let head = &p[..=i];
                let head = if head.chars().all(|c| c == '/') { head } else { head.trim_end_matches('/') };
                (head.to_string(), p[i + 1..].to_string())
            }
            None => (String::new(), p.to_string()),
        }
    };
    Ok(match name {
        "join" => {
            if args.is_empty() {
                return Err(Error::python("TypeError: join() missing 1 required positional argument"));
            }
            let mut out = text_arg(name, &args[0])?;
            for a in &args[1..] {
                let b = text_arg(name, a)?;
                if b.starts_with('/') {
                    out = b;
                } else if out.is_empty() || out.ends_with('/') {
                    out.push_str(&b);
                } else {
                    out.push('/');
                    out.push_str(&b);
                }
            }
            Value::str(&out)
        }
        "basename" => Value::str(&split(&one()?).1),
        "dirname" => Value::str(&split(&one()?).0),
        "split" => {
            let (h, t) = split(&one()?);
            Value::tuple(vec![Value::str(&h), Value::str(&t)])
        }
        "splitext" => {
            let p = one()?;
            let base_start = p.rfind('/').map(|i| i + 1).unwrap_or(0);
            let base = &p[base_start..];
            let dot = base.rfind('.').filter(|&i| base[..i].chars().any(|c| c != '.'));
            match dot {
                Some(i) => Value::tuple(vec![Value::str(&p[..base_start + i]), Value::str(&base[i..])]),
                None => Value::tuple(vec![Value::str(&p), Value::str("")]),
            }
        }
        "isabs" => Value::Bool(one()?.starts_with('/')),
        "normpath" => {
            let p = one()?;
            if p.is_empty() {
                return Ok(Value::str("."));
            }
            let lead = if p.starts_with("//") && !p.starts_with("///") { 2 } else { usize::from(p.starts_with('/')) };
            let mut parts: Vec<&str> = Vec::new();
            for c in p.split('/') {
                match c {
                    "" | "." => {}
                    ".." if parts.last().is_some_and(|l| *l != "..") => {
                        parts.pop();
                    }
                    ".." if lead > 0 => {}
                    c => parts.push(c),
                }
            }
            let s = "/".repeat(lead) + &parts.join("/");
            Value::str(if s.is_empty() { "." } else { &s })
        }
        _ => return Err(refused(&format!("os.path.{name}"), "reaching the file system outside the run's units")),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s(v: &str) -> Value {
        Value::str(v)
    }
    fn text(v: Value) -> String {
        super::super::format::repr(&v)
    }

    /// Expected values are CPython 3.11's posixpath on the same arguments.
    #[test]
    fn os_path_as_python() {
        assert_eq!(text(call_os_path("join", &[s("a"), s("b"), s("c.med")]).unwrap()), "'a/b/c.med'");
        assert_eq!(text(call_os_path("join", &[s("a/"), s("/abs"), s("x")]).unwrap()), "'/abs/x'");
        assert_eq!(text(call_os_path("basename", &[s("/x/y/z.comm")]).unwrap()), "'z.comm'");
        assert_eq!(text(call_os_path("dirname", &[s("/x/y/z.comm")]).unwrap()), "'/x/y'");
        assert_eq!(text(call_os_path("dirname", &[s("/z")]).unwrap()), "'/'");
        assert_eq!(text(call_os_path("splitext", &[s("a/b.tar.gz")]).unwrap()), "('a/b.tar', '.gz')");
        assert_eq!(text(call_os_path("splitext", &[s(".bashrc")]).unwrap()), "('.bashrc', '')");
        assert_eq!(text(call_os_path("split", &[s("a/b/")]).unwrap()), "('a/b', '')");
        assert_eq!(text(call_os_path("normpath", &[s("a//b/./c/../d")]).unwrap()), "'a/b/d'");
        assert_eq!(text(call_os_path("normpath", &[s("/../x")]).unwrap()), "'/x'");
        assert!(call_os_path("exists", &[s("x")]).is_err());
    }

    #[test]
    fn sys_and_re_import_but_stop_on_use() {
        for (m, attr) in [("sys", "argv"), ("re", "compile")] {
            let module = import(m, false).unwrap();
            let e = get_attr(&module, attr).unwrap_err();
            assert!(e.msg.contains(&format!("{m}.{attr}")) && e.msg.contains("not supported"), "{}", e.msg);
        }
    }

    #[test]
    fn the_runner_predefines_math_and_the_commands_api() {
        let g: Scope = Default::default();
        crate::interp::predefine(&g, "DEBUT()\nx = pi\n");
        assert!(g.borrow().contains_key("sqrt") && g.borrow().contains_key("CA") && g.borrow().contains_key("CO"));
        let g: Scope = Default::default();
        predefine(&g, "from code_aster import CA\nCA.init()\n");
        assert!(g.borrow().is_empty(), "a file that imports the commands itself gets nothing");
        let g: Scope = Default::default();
        predefine(&g, "from code_aster.Commands import *\n");
        assert!(g.borrow().is_empty());
    }
}
