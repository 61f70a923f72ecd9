//! No command file ends in a Rust panic or a runaway: formatting edge cases give CPython's results
//! or its exceptions as located `<F>` errors (issue 9).

use aster::interp::{format, Interp};
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::Path;
use std::rc::Rc;

/// `repr(r)` of `r = EXPR` (or `len=N` when longer than 200), else the Python exception as the
/// interpreter reports it.
fn eval(expr: &str) -> String {
    let src = format!("import math\nr = {expr}\n");
    let module = aster::syntax::parse_module(&src).map_err(|e| format!("SyntaxError: {}", e.message));
    let module = match module {
        Ok(m) => m,
        Err(e) => return e,
    };
    let globals = Rc::new(RefCell::new(HashMap::new()));
    let mut it = Interp::new(globals.clone(), None);
    match it.run(&module) {
        Ok(()) => {
            let r = format::repr(&globals.borrow()["r"]);
            if r.chars().count() < 200 {
                r
            } else {
                format!("len={}", format::to_str(&globals.borrow()["r"]).chars().count())
            }
        }
        Err(e) => e.msg,
    }
}

/// Each expression with what CPython 3.11 gives for it (`python3 -c "print(repr(EXPR))"`), except
/// that where CPython raises a bare `MemoryError` after trying to allocate gigabytes, the
/// interpreter raises it before, naming the limit.
const CPYTHON: &[(&str, &str)] = &[
    (r#"'%99999999999999999999d' % 1"#, r#"ValueError: width too big"#),
    (r#"'%*d' % (-3, 1)"#, r#"'1  '"#),
    (r#"'%.2000000000f' % 1"#, r#"MemoryError:"#),
    (r#"'%.99999999999999999999f' % 1"#, r#"ValueError: precision too big"#),
    (r#"'%.2147483648f' % 1"#, r#"ValueError: precision too big"#),
    (r#"'%*d' % (1.5, 1)"#, r#"TypeError: * wants int"#),
    (r#"'%.*f' % (-3, 1.5)"#, r#"'2'"#),
    (r#"'%.*f' % (2**40, 1.5)"#, r#"OverflowError: Python int too large to convert to C int"#),
    (r#"'%c' % 1114112"#, r#"OverflowError: %c arg not in range(0x110000)"#),
    (r#"'%c' % -1"#, r#"OverflowError: %c arg not in range(0x110000)"#),
    (r#"'%c' % 'ab'"#, r#"TypeError: %c requires int or char"#),
    (r#"'%c' % 1.5"#, r#"TypeError: %c requires int or char"#),
    (r#"'%d' % 'a'"#, r#"TypeError: %d format: a real number is required, not str"#),
    (r#"'%x' % 1.5"#, r#"TypeError: %x format: an integer is required, not float"#),
    (r#"'%f' % 'a'"#, r#"TypeError: must be real number, not str"#),
    (r#"'%d' % float('inf')"#, r#"OverflowError: cannot convert float infinity to integer"#),
    (r#"'%d' % float('nan')"#, r#"ValueError: cannot convert float NaN to integer"#),
    (r#"'%d' % 1e30"#, r#"'1000000000000000019884624838656'"#),
    (r#"'%d' % -1e30"#, r#"'-1000000000000000019884624838656'"#),
    (r#"'%x' % True"#, r#"'1'"#),
    (r#"'%(a)d %d' % {'a':1}"#, r#"TypeError: not enough arguments for format string"#),
    (r#"'%(a' % {'a':1}"#, r#"ValueError: incomplete format key"#),
    (r#"'%z' % 1"#, r#"ValueError: unsupported format character 'z' (0x7a) at index 1"#),
    (r#"'%5' % 1"#, r#"ValueError: incomplete format"#),
    (r#"'%' % ()"#, r#"ValueError: incomplete format"#),
    (r#"'%s %s' % (1,)"#, r#"TypeError: not enough arguments for format string"#),
    (r#"'%s' % (1,2)"#, r#"TypeError: not all arguments converted during string formatting"#),
    (r#"'%d' % None"#, r#"TypeError: %d format: a real number is required, not NoneType"#),
    (r#"'%.3d' % 5"#, r#"'005'"#),
    (r#"'%.3x' % 5"#, r#"'005'"#),
    (r#"'%#o' % 8"#, r#"'0o10'"#),
    (r#"'%#.3o' % 8"#, r#"'0o010'"#),
    (r#"'%-05d' % 3"#, r#"'3    '"#),
    (r#"'% d' % 3"#, r#"' 3'"#),
    (r#"'%+ d' % 3"#, r#"'+3'"#),
    (r#"'%5.1s' % 'abc'"#, r#"'    a'"#),
    (r#"'%.3s' % 1.23456"#, r#"'1.2'"#),
    (r#"'%s' % {'a':1}"#, r#""{'a': 1}""#),
    (r#"'%(a)s' % {'a':1}"#, r#"'1'"#),
    (r#"'%*.*f' % (8, 2, 3.14159)"#, r#"'    3.14'"#),
    (r#"'%*s' % ('a', 1)"#, r#"TypeError: * wants int"#),
    (r#"'%e' % 1e300"#, r#"'1.000000e+300'"#),
    (r#"'%a' % 'é'"#, r#""'\\xe9'""#),
    (r#"'%r' % 'é'"#, r#""'é'""#),
    (r#"'%i' % True"#, r#"'1'"#),
    (r#"'%u' % -3"#, r#"'-3'"#),
    (r#"'%ld' % 3"#, r#"'3'"#),
    (r#"'%.0e' % 15"#, r#"'2e+01'"#),
    (r#"'%#.0e' % 15"#, r#"'2.e+01'"#),
    (r#"'%#.0f' % 15"#, r#"'15.'"#),
    (r#"'%#x' % 0"#, r#"'0x0'"#),
    (r#"'%#g' % 0.0"#, r#"'0.00000'"#),
    (r#"'%05s' % 'a'"#, r#"'    a'"#),
    (r#"'%-5c' % 'a'"#, r#"'a    '"#),
    (r#"'%5c' % 97"#, r#"'    a'"#),
    (r#"'%08f' % float('inf')"#, r#"'00000inf'"#),
    (r#"'%08e' % float('-inf')"#, r#"'-0000inf'"#),
    (r#"'%-08d' % 3"#, r#"'3       '"#),
    (r#"'%-#6x' % 255"#, r#"'0xff  '"#),
    (r#"'%#06x' % 255"#, r#"'0x00ff'"#),
    (r#"'%+.3d' % 5"#, r#"'+005'"#),
    (r#"'%x' % -255"#, r#"'-ff'"#),
    (r#"'%#X' % 255"#, r#"'0XFF'"#),
    (r#"'% 05d' % -3"#, r#"'-0003'"#),
    (r#"'%(a)s %(b)s' % {'a':1}"#, r#"KeyError: 'b'"#),
    (r#"'' % {'a':1}"#, r#"''"#),
    (r#"'' % 'a'"#, r#"TypeError: not all arguments converted during string formatting"#),
    (r#"'%(a)s' % (1,)"#, r#"TypeError: format requires a mapping"#),
    (r#"'%(a(b))s' % {'a(b)':1}"#, r#"'1'"#),
    (r#"'%s' % ()"#, r#"TypeError: not enough arguments for format string"#),
    (r#"'%5%' % (1,)"#, r#"ValueError: unsupported format character '%' (0x25) at index 2"#),
    (r#"'%.1100f' % 5e-324"#, r#"len=1102"#),
    (r#"'%.70000f' % 1"#, r#"len=70002"#),
    (r#"'%.65535e' % 1.5"#, r#"len=65541"#),
    (r#"'%3d|%.2f|%-4s|' % (5, 1.23456, 'ab')"#, r#"'  5|1.23|ab  |'"#),
    (r#"'%g' % 0.00001234"#, r#"'1.234e-05'"#),
    (r#"'%.15g' % 0.1"#, r#"'0.1'"#),
    (r#"'%10.4e' % -12.5"#, r#"'-1.2500e+01'"#),
    (r#"'%i%%' % 50"#, r#"'50%'"#),
    (r#"format(1, '99999999999999999999d')"#, r#"ValueError: Too many decimal digits in format string"#),
    (r#"format(1.5, '.99999999999999999999f')"#, r#"ValueError: Too many decimal digits in format string"#),
    (r#"'{:99999999999999999999}'.format(1)"#, r#"ValueError: Too many decimal digits in format string"#),
    (r#"format(1, '5.')"#, r#"ValueError: Format specifier missing precision"#),
    (r#"format(1,'dd')"#, r#"ValueError: Invalid format specifier 'dd' for object of type 'int'"#),
    (r#"format(1.5,'ff')"#, r#"ValueError: Invalid format specifier 'ff' for object of type 'float'"#),
    (r#"format('a','ss')"#, r#"ValueError: Invalid format specifier 'ss' for object of type 'str'"#),
    (r#"format(1, '<<5')"#, r#"'1<<<<'"#),
    (r#"format(1, ',_')"#, r#"ValueError: Cannot specify both ',' and '_'."#),
    (r#"format('a', '+')"#, r#"ValueError: Sign not allowed in string format specifier"#),
    (r#"format('a', '#')"#, r#"ValueError: Alternate form (#) not allowed in string format specifier"#),
    (r#"format('a', ',')"#, r#"ValueError: Cannot specify ',' with 's'."#),
    (r#"format(97, '#c')"#, r#"ValueError: Alternate form (#) not allowed with integer format specifier 'c'"#),
    (r#"format(97, 'n')"#, r#"'97'"#),
    (r#"format(1234, ',n')"#, r#"ValueError: Cannot specify ',' with 'n'."#),
    (r#"format(1.5, ',n')"#, r#"ValueError: Cannot specify ',' with 'n'."#),
    (r#"format(1.5, '#.0e')"#, r#"'2.e+00'"#),
    (r#"format(1.5, '#.0f')"#, r#"'2.'"#),
    (r#"format(1.5, '#.0')"#, r#"'2.e+00'"#),
    (r#"format(15.0, '#')"#, r#"'15.0'"#),
    (r#"format(1e16, '')"#, r#"'1e+16'"#),
    (r#"format(1e16, ',')"#, r#"'1e+16'"#),
    (r#"format(1234.5, '_')"#, r#"'1_234.5'"#),
    (r#"format(1234.5, '_g')"#, r#"'1_234.5'"#),
    (r#"format(-0.0, 'f')"#, r#"'-0.000000'"#),
    (r#"format(float('nan'), '+f')"#, r#"'+nan'"#),
    (r#"format(float('-inf'), '08f')"#, r#"'-0000inf'"#),
    (r#"format(1.5, '.0%')"#, r#"'150%'"#),
    (r#"format(True, 'c')"#, r#"'\x01'"#),
    (r#"format(5, '.3')"#, r#"ValueError: Precision not allowed in integer format specifier"#),
    (r#"format(5, '.3f')"#, r#"'5.000'"#),
    (r#"format(5, '%')"#, r#"'500.000000%'"#),
    (r#"format(1.5,'.1n')"#, r#"'2'"#),
    (r#"format(12345678, '_o')"#, r#"'5706_0516'"#),
    (r#"format(-255, '#x')"#, r#"'-0xff'"#),
    (r#"format(-255, '#010x')"#, r#"'-0x00000ff'"#),
    (r#"format(255, '=+8')"#, r#"'+    255'"#),
    (r#"format('ab','x<5')"#, r#"'abxxx'"#),
    (r#"format(1,'0=5')"#, r#"'00001'"#),
    (r#"format(1.5, '=^8')"#, r#"'==1.5==='"#),
    (r#"format(12, 'x^8')"#, r#"'xxx12xxx'"#),
    (r#"format(1.5, '012,.2f')"#, r#"'0,000,001.50'"#),
    (r#"format(1234567, '012,')"#, r#"'0,001,234,567'"#),
    (r#"format(-1234567, '012,')"#, r#"'-001,234,567'"#),
    (r#"format(0.0001, '.1')"#, r#"'0.0001'"#),
    (r#"format(123.0, '.3')"#, r#"'1.23e+02'"#),
    (r#"format(1.0, '.1')"#, r#"'1e+00'"#),
    (r#"format(float('nan'), '.3')"#, r#"'nan'"#),
    (r#"format(1e16, '.17')"#, r#"'1e+16'"#),
    (r#"format(1.5, '.0')"#, r#"'2e+00'"#),
    (r#"format(100.0, '.2')"#, r#"'1e+02'"#),
    (r#"format(2.0, '.3')"#, r#"'2.0'"#),
    (r#"format(1114112,'c')"#, r#"OverflowError: %c arg not in range(0x110000)"#),
    (r#"format(-1,'c')"#, r#"OverflowError: %c arg not in range(0x110000)"#),
    (r#"format(97,'+c')"#, r#"ValueError: Sign not allowed with integer format specifier 'c'"#),
    (r#"format(97,',c')"#, r#"ValueError: Cannot specify ',' with 'c'."#),
    (r#"format(True,'5')"#, r#"'    1'"#),
    (r#"format(True,'d')"#, r#"'1'"#),
    (r#"format(True, '')"#, r#"'True'"#),
    (r#"format(None, '')"#, r#"'None'"#),
    (r#"format(None, '5')"#, r#"TypeError: unsupported format string passed to NoneType.__format__"#),
    (r#"format([1], 's')"#, r#"TypeError: unsupported format string passed to list.__format__"#),
    (r#"format(12345,'_x')"#, r#"'3039'"#),
    (r#"format(12345,',x')"#, r#"ValueError: Cannot specify ',' with 'x'."#),
    (r#"format(12345,'_b')"#, r#"'11_0000_0011_1001'"#),
    (r#"format('a','=10')"#, r#"ValueError: '=' alignment not allowed in string format specifier"#),
    (r#"format('a','010')"#, r#"'a000000000'"#),
    (r#"format(1,'<05')"#, r#"'10000'"#),
    (r#"format(1.25,'.1f')"#, r#"'1.2'"#),
    (r#"format(0.125,'.2f')"#, r#"'0.12'"#),
    (r#"format(1e300, 'f')"#, r#"len=308"#),
    (r#"format(1.5, '.2000000000f')"#, r#"MemoryError:"#),
    (r#"format(1, '2000000000d')"#, r#"MemoryError:"#),
    (r#"'{!}'.format(1)"#, r#"ValueError: unmatched '{' in format spec"#),
    (r#"'{!x}'.format(1)"#, r#"ValueError: Unknown conversion specifier x"#),
    (r#"'{!rr}'.format(1)"#, r#"ValueError: expected ':' after conversion specifier"#),
    (r#"'{!a}'.format('é')"#, r#""'\\xe9'""#),
    (r#"'}'.format()"#, r#"ValueError: Single '}' encountered in format string"#),
    (r#"'a}b'.format()"#, r#"ValueError: Single '}' encountered in format string"#),
    (r#"'{:{:{}}}'.format(1,2,3)"#, r#"ValueError: Max string recursion exceeded"#),
    (r#"'{:{}}'.format(1,5)"#, r#"'    1'"#),
    (r#"'{'.format()"#, r#"ValueError: Single '{' encountered in format string"#),
    (r#"'{0:{1}}'.format(1,5)"#, r#"'    1'"#),
    (r#"'{:{w}}'.format(1, w=9999999999999)"#, r#"MemoryError:"#),
    (r#"'{0[1]}'.format([1,2])"#, r#"'2'"#),
    (r#"'{99999999999999999999999}'.format(1)"#, r#"ValueError: Too many decimal digits in format string"#),
    (r#"'{} {}'.format(1)"#, r#"IndexError: Replacement index 1 out of range for positional args tuple"#),
    (r#"'{x}'.format(y=1)"#, r#"KeyError: 'x'"#),
    (r#"f'{1.5:{10}.{3}f}'"#, r#"'     1.500'"#),
    (r#"f'{"é"!a}'"#, r#""'\\xe9'""#),
    (r#"f'{3!r:>5}'"#, r#"'    3'"#),
    (r#"'ab'.ljust(10**12)"#, r#"MemoryError:"#),
    (r#"'ab'.zfill(10**12)"#, r#"MemoryError:"#),
    (r#"'ab'.center(7, 'xy')"#, r#"TypeError: The fill character must be exactly one character long"#),
    (r#"'ab'.center(7, '*')"#, r#"'***ab**'"#),
    (r#"'ab'.rjust(5, 1)"#, r#"TypeError: The fill character must be a unicode character, not int"#),
    (r#"'a' * 10**12"#, r#"MemoryError:"#),
    (r#"[0] * 1000 * 10**7"#, r#"MemoryError:"#),
    (r#"chr(-1)"#, r#"ValueError: chr() arg not in range(0x110000)"#),
    (r#"chr(0x110000)"#, r#"ValueError: chr() arg not in range(0x110000)"#),
    (r#"chr(-4294967199)"#, r#"OverflowError: Python int too large to convert to C int"#),
    (r#"chr(97)"#, r#"'a'"#),
];

#[test]
fn formatting_as_cpython() {
    let mut bad = Vec::new();
    for (expr, want) in CPYTHON {
        let got = eval(expr);
        let ok = if *want == "MemoryError:" {
            got.starts_with("MemoryError: ") && got.contains("exceeds the limit of")
        } else {
            got == *want
        };
        if !ok {
            bad.push(format!("{expr}\n    CPython: {want}\n    aster:   {got}"));
        }
    }
    assert!(bad.is_empty(), "{} of {} cases differ:\n{}", bad.len(), CPYTHON.len(), bad.join("\n"));
}

struct Run {
    code: i32,
    stdout: String,
    stderr: String,
    mess: String,
}

/// `aster run DIR/FILE --out DIR` with extra arguments and environment.
fn aster_run(dir: &Path, file: &str, args: &[&str], env: &[(&str, &str)]) -> Run {
    let mut cmd = crate::common::aster();
    cmd.arg("run").arg(dir.join(file)).args(["--out", dir.to_str().unwrap()]).args(args);
    for (k, v) in env {
        cmd.env(k, v);
    }
    let out = cmd.output().unwrap();
    let stem = Path::new(file).file_stem().unwrap().to_str().unwrap();
    Run {
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
        mess: std::fs::read_to_string(dir.join(format!("{stem}.mess"))).unwrap_or_default(),
    }
}

#[test]
fn the_issue_format_cases_under_aster_run() {
    let dir = crate::scratch!("format");
    std::fs::write(dir.join("width.comm"), "DEBUT()\nx = '%99999999999999999999d' % 1\nFIN()\n").unwrap();
    let r = aster_run(&dir, "width.comm", &["-q"], &[]);
    assert_eq!(r.code, 2, "stderr: {}", r.stderr);
    assert!(r.stderr.contains("<F> width.comm:2:5: ValueError: width too big"), "stderr: {}", r.stderr);
    assert!(!r.stderr.contains("panicked"), "stderr: {}", r.stderr);
    assert!(r.mess.contains("DIAGNOSTIC JOB : <F>_ERROR"), "{}", r.mess);

    std::fs::write(dir.join("left.comm"), "DEBUT()\nprint('[' + '%*d' % (-3, 1) + ']')\nFIN()\n").unwrap();
    let r = aster_run(&dir, "left.comm", &[], &[]);
    assert_eq!(r.code, 0, "stderr: {}", r.stderr);
    assert!(r.stdout.contains("[1  ]"), "stdout: {}", r.stdout);
}

/// The test hook ASTER_INJECT_PANIC makes the stage of a command panic: the run must stop with a
/// located `<F> ... internal error`, print no raw panic or backtrace, exit with 2 and deliver no
/// result file (junction_2d writes unit 80 with IMPR_RESU before its TEST_RESU).
#[test]
fn an_internal_panic_is_a_located_error_and_delivers_nothing() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = crate::scratch!("panic");
    std::fs::copy(root.join("comm/junction_2d.comm"), dir.join("junction_2d.comm")).unwrap();
    let mesh = format!("20={}", root.join("med/junction_quad8.med").display());
    let rmed = dir.join("junction_2d.rmed");
    let units = ["--unit", &mesh, "--unit", &format!("80={}", rmed.display())];

    // Without the hook the result is delivered: the assertions below are not vacuous.
    let r = aster_run(&dir, "junction_2d.comm", &units, &[]);
    assert_eq!(r.code, 0, "stderr: {}", r.stderr);
    assert!(rmed.exists());
    std::fs::remove_file(&rmed).unwrap();

    let r =
        aster_run(&dir, "junction_2d.comm", &units, &[("ASTER_INJECT_PANIC", "TEST_RESU"), ("RUST_BACKTRACE", "1")]);
    assert_eq!(r.code, 2, "stderr: {}", r.stderr);
    let located = "<F> junction_2d.comm:61:1: TEST_RESU: internal error: panic injected in TEST_RESU";
    assert!(r.stderr.contains(located), "stderr: {}", r.stderr);
    assert!(r.mess.contains(located), "mess tail: {}", &r.mess[r.mess.len().saturating_sub(400)..]);
    assert!(r.stdout.contains(located), "the console shows the <F> line: {}", r.stdout);
    assert!(r.mess.contains("DIAGNOSTIC JOB : <F>_ERROR"));
    for text in [&r.stdout, &r.stderr] {
        assert!(!text.contains("panicked at") && !text.contains("stack backtrace"), "raw panic output:\n{text}");
    }
    let mut left: Vec<String> =
        std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    left.sort();
    // The message and result text files of the run (.mess, .resu) only: no unit 80, no temporary.
    assert_eq!(left, ["junction_2d.comm", "junction_2d.mess", "junction_2d.resu"]);
}

/// `while True: pass` stops at `--time-limit` with a located error, and at the .export's
/// `P time_limit` without it. The wall-time bounds are generous: functional, not a benchmark.
#[test]
fn a_runaway_file_stops_at_its_time_limit() {
    let dir = crate::scratch!("time");
    std::fs::write(dir.join("loop.comm"), "DEBUT()\nn = 0\nwhile True:\n    pass\nFIN()\n").unwrap();
    let t0 = std::time::Instant::now();
    let r = aster_run(&dir, "loop.comm", &["-q", "--time-limit", "2"], &[]);
    let wall = t0.elapsed().as_secs_f64();
    assert_eq!(r.code, 2, "stderr: {}", r.stderr);
    assert!(r.stderr.contains("<F> loop.comm:3:1: time limit of 2 s exceeded"), "stderr: {}", r.stderr);
    assert!(r.mess.contains("DIAGNOSTIC JOB : <F>_ERROR"));
    assert!((1.9..3.0).contains(&wall), "stopped after {wall:.2} s");

    std::fs::write(dir.join("loop.export"), "P time_limit 1\nF comm loop.comm D 1\n").unwrap();
    let t0 = std::time::Instant::now();
    let r = aster_run(&dir, "loop.export", &["-q"], &[]);
    let wall = t0.elapsed().as_secs_f64();
    assert_eq!(r.code, 2, "stderr: {}", r.stderr);
    assert!(r.stderr.contains("<F> loop.comm:3:1: time limit of 1 s exceeded"), "stderr: {}", r.stderr);
    assert!(wall < 2.5, "stopped after {wall:.2} s");

    // A recursion inside a list comprehension, between commands: stopped where it is.
    std::fs::write(
        dir.join("fib.comm"),
        "DEBUT()\ndef f(n):\n    return n if n < 2 else f(n - 1) + f(n - 2)\nx = [f(30) for i in range(100)]\nFIN()\n",
    )
    .unwrap();
    let r = aster_run(&dir, "fib.comm", &["-q", "--time-limit", "0.5"], &[]);
    assert!(r.stderr.contains("<F> fib.comm:3:5: time limit of 0.5 s exceeded"), "stderr: {}", r.stderr);
}

/// DEFI_LIST_REEL with NOMBRE=2**62 ran for ever (found by tests/fuzz_pipeline.rs); lists too long to
/// hold and bounds that are not finite are refused by name.
#[test]
fn list_sizes_and_bounds_are_checked() {
    let dir = crate::scratch!("lists");
    let lists = [
        // NOMBRE=2**62 ran for ever, pushing values.
        (
            "INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=2**62)",
            "l.comm:2:31: DEFI_LIST_REEL: INTERVALLE/NOMBRE: NOMBRE=4611686018427387904 makes a list of more than 10000000 values",
        ),
        ("INTERVALLE=_F(JUSQU_A=1.0, PAS=1e-308)", "DEFI_LIST_REEL: INTERVALLE/PAS: PAS=1e-308 makes a list of more"),
        ("INTERVALLE=_F(JUSQU_A=float('inf'), PAS=0.5)", "DEFI_LIST_REEL: INTERVALLE/JUSQU_A: JUSQU_A=inf is not a finite"),
        ("INTERVALLE=_F(JUSQU_A=float('nan'), NOMBRE=2)", "DEFI_LIST_REEL: INTERVALLE/JUSQU_A: JUSQU_A=nan is not a finite"),
    ];
    for (interval, want) in lists {
        std::fs::write(dir.join("l.comm"), format!("DEBUT()\nL = DEFI_LIST_REEL(DEBUT=0.0, {interval})\nFIN()\n"))
            .unwrap();
        let r = aster_run(&dir, "l.comm", &["-q", "--time-limit", "20"], &[]);
        assert_eq!(r.code, 2, "{interval}: {}", r.stderr);
        assert!(r.stderr.contains(want), "{interval}: expected '{want}' in\n{}", r.stderr);
    }
}

/// A nan or an infinity in the material or the loads is named, not called a singular system.
#[test]
fn non_finite_data_is_named() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = crate::scratch!("non-finite");
    let src = std::fs::read_to_string(root.join("comm/block_tension_2d.comm")).unwrap();
    let mesh = format!("20={}", root.join("med/block_quad8.med").display());
    for (from, to, want) in [
        ("E = 210000.0", "E = float('nan')", "MECA_STATIQUE: CHAM_MATER: the stiffness is not finite"),
        ("NU = 0.3", "NU = 0.5", "MECA_STATIQUE: CHAM_MATER: the stiffness is not finite"),
        ("P = 100.0", "P = float('inf')", "MECA_STATIQUE: EXCIT: the loads are not finite"),
    ] {
        std::fs::write(dir.join("b.comm"), src.replace(from, to)).unwrap();
        let r = aster_run(&dir, "b.comm", &["-q", "--unit", &mesh], &[]);
        assert_eq!(r.code, 2, "{to}: {}", r.stderr);
        assert!(r.stderr.contains("b.comm:23:") && r.stderr.contains(want), "{to}: {}", r.stderr);
    }
}
