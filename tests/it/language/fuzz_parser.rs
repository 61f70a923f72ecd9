//! A bounded mutation fuzzer for the parser: random and mutated command-file
//! text must never panic, overflow the stack or take long. The corpus is the
//! command files of ../shared/astest and comm/ (when present) plus built-in
//! snippets. Time budget: FUZZ_SECONDS (default 8 s); the seed is fixed, so a
//! run is reproducible (FUZZ_SEED overrides it).

use std::path::Path;
use std::time::{Duration, Instant};

use crate::common::Rng;

const TOKENS: &[&str] = &[
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    ":",
    ",",
    "=",
    "==",
    "'",
    "\"",
    "\"\"\"",
    "'''",
    "\\",
    "\n",
    "    ",
    "\t",
    "#",
    "_F(",
    "lambda x: ",
    "if ",
    "elif ",
    "else:",
    "for i in ",
    "while ",
    "def f(",
    "return ",
    "f\"{",
    "}",
    "%",
    "**",
    "*",
    "1e",
    "1.",
    ".5",
    "0x",
    "é",
    "\r\n",
    ";",
    "not ",
    " in ",
    "is ",
    "DEBUT(",
    "reuse=",
    "**kw",
    "[i for i in range(3)]",
    "{'a': 1}",
    "import math",
    "from math import *",
    "\\\n",
    "r'",
    "b'",
    "\u{feff}",
    "\0",
];

const SNIPPETS: &[&str] = &[
    "DEBUT()\nF = DEFI_FONCTION(NOM_PARA='X', VALE=(0., 1., 1., 2.),\n    PROL_DROITE='LINEAIRE')\nFIN()\n",
    "def f(x, y=2, *a, **k):\n    if x:\n        return [i * y for i in range(x) if i % 2]\n    else:\n        return {k: v for k, v in zip('ab', (1, 2))}\n",
    "s = f'{1 + 2:>{4}} {\"a\"!r}' + '%5.2f %s' % (3.14159, [1, (2,)])\nt = \"\"\"multi\nline\"\"\"\n",
    "for i, (a, b) in enumerate([(1, 2), (3, 4)]):\n    while a < b:\n        a += 1\n    else:\n        pass\nx = a if b else -1 ** 2\n",
    "T = CALC_TABLE(reuse=T, TABLE=T, ACTION=(_F(OPERATION='FILTRE', NOM_PARA='N', VALE_I=2),))\n",
];

fn corpus() -> Vec<String> {
    let mut v: Vec<String> = SNIPPETS.iter().map(|s| s.to_string()).collect();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for dir in [root.join("../shared/astest"), root.join("comm")] {
        if let Ok(rd) = std::fs::read_dir(&dir) {
            let mut paths: Vec<_> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
            paths.sort();
            for p in paths {
                if p.extension().map(|x| x == "comm").unwrap_or(false) {
                    if let Ok(b) = std::fs::read(&p) {
                        v.push(String::from_utf8_lossy(&b).into_owned());
                    }
                }
            }
        }
    }
    v
}

fn char_floor(s: &str, mut i: usize) -> usize {
    i = i.min(s.len());
    while !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn mutate(rng: &mut Rng, src: &str) -> String {
    let mut s = src.to_string();
    for _ in 0..1 + rng.below(6) {
        let len = s.len();
        let a = char_floor(&s, rng.below(len + 1));
        let b = char_floor(&s, a + rng.below(64).min(len - a));
        match rng.below(6) {
            0 => s.replace_range(a..b, ""),
            1 => {
                let piece = s[a..b].to_string();
                s.insert_str(a, &piece);
            }
            2 | 3 => s.insert_str(a, TOKENS[rng.below(TOKENS.len())]),
            4 => s.truncate(a),
            _ => {
                let n = rng.below(4) + 1;
                let junk: String = (0..n).map(|_| (b' ' + rng.below(95) as u8) as char).collect();
                s.replace_range(a..b, &junk);
            }
        }
    }
    s
}

fn random_text(rng: &mut Rng) -> String {
    (0..rng.below(40)).map(|_| TOKENS[rng.below(TOKENS.len())]).collect()
}

#[test]
fn parser_survives_mutated_and_random_text() {
    let budget =
        Duration::from_secs_f64(std::env::var("FUZZ_SECONDS").ok().and_then(|s| s.parse().ok()).unwrap_or(8.0));
    let seed = std::env::var("FUZZ_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(0x5EED_A57E_u64);
    let mut rng = Rng(seed);
    let corpus = corpus();
    let start = Instant::now();
    let (mut cases, mut parsed) = (0u64, 0u64);
    let mut slowest = Duration::ZERO;
    while start.elapsed() < budget {
        let text = if rng.below(10) == 0 {
            random_text(&mut rng)
        } else {
            let pick = rng.below(corpus.len());
            mutate(&mut rng, &corpus[pick])
        };
        let t0 = Instant::now();
        let r = std::panic::catch_unwind(|| aster::syntax::parse_module(&text).is_ok());
        let dt = t0.elapsed();
        slowest = slowest.max(dt);
        match r {
            Ok(ok) => parsed += ok as u64,
            Err(_) => panic!("the parser panicked on this input (seed {seed}, case {cases}):\n{text:?}"),
        }
        assert!(dt < Duration::from_secs(2), "parsing took {dt:?} (seed {seed}, case {cases}):\n{text:?}");
        cases += 1;
    }
    // Pathological nesting is refused, not recursed into.
    let deep = format!("x = {}1{}\n", "(".repeat(100_000), ")".repeat(100_000));
    let e = aster::syntax::parse_module(&deep).unwrap_err();
    assert!(e.message.contains("nested"), "{}", e.message);
    println!("fuzz: {cases} cases in {:?}, {parsed} parsed, slowest {slowest:?}, seed {seed}", start.elapsed());
    assert!(cases > 100, "the fuzzer ran too few cases ({cases})");
}
