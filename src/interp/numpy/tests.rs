//! The numpy subset against numpy: each expression below was evaluated by numpy 2.4.6 (CPython 3.11),
//! and its text (`str` of an array, `repr` of a Python number, bool or list) stored beside it.
//! `scripts/numpy_cases.py` evaluates every case with numpy and prints those whose stored text differs.

use crate::interp::{format, Interp, Scope};

fn eval(expr: &str) -> String {
    let globals: Scope = Default::default();
    let src = format!("import numpy as np\nr = {expr}\n");
    let module = crate::syntax::parse_module(&src).unwrap_or_else(|e| panic!("{expr}: {}", e.message));
    Interp::new(globals.clone(), None).run(&module).unwrap_or_else(|e| panic!("{expr}: {}", e.msg));
    let r = globals.borrow().get("r").cloned().unwrap();
    match &r {
        crate::interp::Value::Str(s) => s.to_string(),
        crate::interp::Value::Array(_) => format::to_str(&r),
        v => format::repr(v),
    }
}

const CASES: &[(&str, &str)] = &[
    ("np.array([1.0, 2.5, 3.0])", "[1.  2.5 3. ]"),
    ("np.array([[1, 2], [3, 4]])", "[[1 2]\n [3 4]]"),
    ("np.array([[1.5, -2.0], [3.25, 4.0]])", "[[ 1.5  -2.  ]\n [ 3.25  4.  ]]"),
    ("np.zeros(3)", "[0. 0. 0.]"),
    ("np.zeros((2, 3))", "[[0. 0. 0.]\n [0. 0. 0.]]"),
    ("np.ones(4)", "[1. 1. 1. 1.]"),
    ("np.full(3, 7.5)", "[7.5 7.5 7.5]"),
    ("np.linspace(0.0, 1.0, 5)", "[0.   0.25 0.5  0.75 1.  ]"),
    ("np.linspace(0, 1, 4, endpoint=False)", "[0.   0.25 0.5  0.75]"),
    ("np.arange(5)", "[0 1 2 3 4]"),
    ("np.arange(0.0, 1.0, 0.25)", "[0.   0.25 0.5  0.75]"),
    ("np.arange(1, 10, 3)", "[1 4 7]"),
    ("np.eye(3)", "[[1. 0. 0.]\n [0. 1. 0.]\n [0. 0. 1.]]"),
    ("np.diag([1.0, 2.0])", "[[1. 0.]\n [0. 2.]]"),
    ("np.array([1e-5, 1.0, 1000.0])", "[1.e-05 1.e+00 1.e+03]"),
    ("np.array([0.1 + 0.2, 1.0 / 3.0])", "[0.3        0.33333333]"),
    ("np.array([True, False, True])", "[ True False  True]"),
    ("repr(np.array([1.0, 2.5]))", "array([1. , 2.5])"),
    ("repr(np.array([[1, 2], [3, 4]]))", "array([[1, 2],\n       [3, 4]])"),
    (
        "np.linspace(0.0, 10.0, 21)",
        "[ 0.   0.5  1.   1.5  2.   2.5  3.   3.5  4.   4.5  5.   5.5  6.   6.5\n  7.   7.5  8.   8.5  9.   9.5 10. ]",
    ),
    ("np.array([1.0, 2.0, 3.0]) * 2 + 1", "[3. 5. 7.]"),
    ("2.0 / np.array([1.0, 4.0, 8.0])", "[2.   0.5  0.25]"),
    ("np.array([1, 2, 3]) * 2", "[2 4 6]"),
    ("np.array([1, 2, 3]) / 2", "[0.5 1.  1.5]"),
    ("np.array([7, -7]) // 2", "[ 3 -4]"),
    ("np.array([7.0, -7.0]) % 3", "[1. 2.]"),
    ("np.array([2.0, 3.0]) ** 2", "[4. 9.]"),
    ("np.array([[1.0, 2.0], [3.0, 4.0]]) + np.array([10.0, 20.0])", "[[11. 22.]\n [13. 24.]]"),
    ("np.array([[1.0], [2.0]]) * np.array([1.0, 10.0, 100.0])", "[[  1.  10. 100.]\n [  2.  20. 200.]]"),
    ("-np.array([1.0, -2.0])", "[-1.  2.]"),
    ("[1.0, 2.0] + np.array([3.0, 4.0])", "[4. 6.]"),
    ("np.array([1.0, 5.0, 3.0]) > 2", "[False  True  True]"),
    ("np.array([1, 2]) == np.array([1, 3])", "[ True False]"),
    ("np.arange(10)[2:8:2]", "[2 4 6]"),
    ("np.arange(10)[-1]", "9"),
    ("np.arange(10)[::-3]", "[9 6 3 0]"),
    ("np.array([[1, 2, 3], [4, 5, 6]])[1, 2]", "6"),
    ("np.array([[1, 2, 3], [4, 5, 6]])[:, 1]", "[2 5]"),
    ("np.array([[1, 2, 3], [4, 5, 6]])[1]", "[4 5 6]"),
    ("np.array([[1, 2, 3], [4, 5, 6]])[:, 1:]", "[[2 3]\n [5 6]]"),
    ("np.array([1.0, 5.0, 3.0])[np.array([1.0, 5.0, 3.0]) > 2]", "[5. 3.]"),
    ("np.array([10, 20, 30])[[2, 0]]", "[30 10]"),
    ("np.sqrt(np.array([1.0, 4.0, 2.0]))", "[1.         2.         1.41421356]"),
    ("np.exp(1.0)", "2.718281828459045"),
    ("np.sin(np.array([0.0, np.pi / 2]))", "[0. 1.]"),
    ("np.abs(np.array([-1.5, 2.0]))", "[1.5 2. ]"),
    ("np.sign(np.array([-2.0, 0.0, 3.0]))", "[-1.  0.  1.]"),
    ("np.sum(np.array([[1, 2], [3, 4]]))", "10"),
    ("np.sum(np.array([[1, 2], [3, 4]]), axis=0)", "[4 6]"),
    ("np.array([[1, 2], [3, 4]]).sum(axis=1)", "[3 7]"),
    ("np.max(np.array([3.0, 7.0, 1.0]))", "7.0"),
    ("np.min(np.array([[3.0, 7.0], [1.0, 9.0]]), axis=1)", "[3. 1.]"),
    ("np.mean(np.array([1.0, 2.0, 4.0]))", "2.3333333333333335"),
    ("np.std(np.array([1.0, 2.0, 4.0]))", "1.247219128924647"),
    ("np.median(np.array([5.0, 1.0, 3.0, 2.0]))", "2.5"),
    ("np.argmax(np.array([1.0, 9.0, 3.0]))", "1"),
    ("np.cumsum(np.array([1, 2, 3]))", "[1 3 6]"),
    ("np.diff(np.array([1.0, 4.0, 9.0]))", "[3. 5.]"),
    ("np.dot(np.array([1.0, 2.0, 3.0]), np.array([4.0, 5.0, 6.0]))", "32.0"),
    ("np.dot(np.array([[1.0, 2.0], [3.0, 4.0]]), np.array([1.0, 1.0]))", "[3. 7.]"),
    ("np.dot(np.array([[1.0, 2.0], [3.0, 4.0]]), np.array([[0.0, 1.0], [1.0, 0.0]]))", "[[2. 1.]\n [4. 3.]]"),
    ("np.outer(np.array([1.0, 2.0]), np.array([3.0, 4.0, 5.0]))", "[[ 3.  4.  5.]\n [ 6.  8. 10.]]"),
    ("np.cross(np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]))", "[0. 0. 1.]"),
    ("np.linalg.norm(np.array([3.0, 4.0]))", "5.0"),
    ("np.linalg.norm(np.array([[1.0, 2.0], [3.0, 4.0]]))", "5.477225575051661"),
    ("np.linalg.norm(np.array([3.0, -4.0]), np.inf)", "4.0"),
    ("np.linalg.solve(np.array([[2.0, 1.0], [1.0, 3.0]]), np.array([3.0, 5.0]))", "[0.8 1.4]"),
    ("np.linalg.det(np.array([[2.0, 1.0], [1.0, 3.0]]))", "5.000000000000001"),
    ("np.linalg.inv(np.array([[2.0, 0.0], [0.0, 4.0]]))", "[[0.5  0.  ]\n [0.   0.25]]"),
    ("np.interp(2.5, [1.0, 2.0, 3.0], [10.0, 20.0, 40.0])", "30.0"),
    ("np.interp(np.array([0.0, 1.5, 5.0]), [1.0, 2.0, 3.0], [10.0, 20.0, 40.0])", "[10. 15. 40.]"),
    ("np.allclose(np.array([1.0, 2.0]), np.array([1.0, 2.0000001]))", "True"),
    ("np.allclose(np.array([1.0, 2.0]), np.array([1.0, 2.1]))", "False"),
    ("np.isclose(np.array([1.0, 2.0]), np.array([1.0, 2.1]))", "[ True False]"),
    ("np.where(np.array([1.0, -1.0, 2.0]) > 0, 1.0, 0.0)", "[1. 0. 1.]"),
    ("np.where(np.array([0, 3, 0, 4]) > 0)[0]", "[1 3]"),
    ("np.reshape(np.arange(6), (2, 3))", "[[0 1 2]\n [3 4 5]]"),
    ("np.arange(6).reshape(3, 2)", "[[0 1]\n [2 3]\n [4 5]]"),
    ("np.arange(6).reshape((3, -1)).T", "[[0 2 4]\n [1 3 5]]"),
    ("np.transpose(np.array([[1, 2, 3], [4, 5, 6]]))", "[[1 4]\n [2 5]\n [3 6]]"),
    ("np.concatenate([np.array([1.0, 2.0]), np.array([3.0])])", "[1. 2. 3.]"),
    ("np.vstack([np.array([1.0, 2.0]), np.array([3.0, 4.0])])", "[[1. 2.]\n [3. 4.]]"),
    ("np.hstack([np.array([1.0, 2.0]), np.array([3.0, 4.0])])", "[1. 2. 3. 4.]"),
    ("np.append(np.array([1, 2]), 3)", "[1 2 3]"),
    ("np.around(np.array([1.25, 2.35, -0.5]), 1)", "[ 1.2  2.4 -0.5]"),
    ("np.round(np.array([0.5, 1.5, 2.5]))", "[0. 2. 2.]"),
    ("np.minimum(np.array([1.0, 5.0]), 3.0)", "[1. 3.]"),
    ("np.maximum(np.array([1.0, 5.0]), np.array([2.0, 2.0]))", "[2. 5.]"),
    ("np.trapz(np.array([1.0, 2.0, 3.0]), np.array([0.0, 1.0, 3.0]))", "6.5"),
    ("np.arctan2(1.0, 1.0)", "0.7853981633974483"),
    ("np.log10(np.array([1.0, 100.0]))", "[0. 2.]"),
    ("np.array([1.0, 2.0]).tolist()", "[1.0, 2.0]"),
    ("np.array([[1, 2], [3, 4]]).tolist()", "[[1, 2], [3, 4]]"),
    ("np.array([[1, 2], [3, 4]]).shape", "(2, 2)"),
    ("np.zeros((2, 3)).size", "6"),
    ("len(np.zeros((4, 2)))", "4"),
    ("sum(np.array([1.0, 2.0, 3.5]))", "6.5"),
    ("max(np.array([1.0, 7.0, 3.5]))", "7.0"),
    ("[x * 2 for x in np.array([1, 2, 3])]", "[2, 4, 6]"),
    ("np.sort(np.array([3.0, 1.0, 2.0]))", "[1. 2. 3.]"),
    ("np.any(np.array([0, 0, 1]))", "True"),
    ("np.all(np.array([[True, False], [True, True]]), axis=0)", "[ True False]"),
    ("np.count_nonzero(np.array([0, 3, 0, 4]))", "2"),
    ("np.logspace(0, 2, 3)", "[  1.  10. 100.]"),
];

#[test]
fn the_subset_agrees_with_numpy() {
    let mut bad = Vec::new();
    for (expr, want) in CASES {
        let got = eval(expr);
        if got != *want {
            bad.push(format!("{expr}\n   numpy: {want}\n   ours:  {got}"));
        }
    }
    assert!(bad.is_empty(), "{} of {} differ:\n{}", bad.len(), CASES.len(), bad.join("\n"));
}

#[test]
fn what_lies_outside_stops_by_name() {
    let globals: Scope = Default::default();
    for (src, name) in [
        ("import numpy as np\nx = np.fft.fft([1.0])\n", "numpy.fft"),
        ("import numpy.fft\n", "numpy.fft"),
        ("import numpy as np\nx = np.zeros((2, 2, 2))\n", "dimensions"),
        ("import numpy as np\nx = np.array([1.0]).argsort()\n", "numpy.ndarray.argsort"),
        ("import numpy as np\nx = np.array([1j])\n", "complex"),
    ] {
        let module = crate::syntax::parse_module(src).unwrap();
        let e = Interp::new(globals.clone(), None).run(&module).unwrap_err();
        assert!(e.msg.contains(name) && e.msg.contains("not supported"), "{src}: {}", e.msg);
        assert_eq!(e.kind, crate::diag::ErrorKind::Unsupported, "{src}");
    }
}

#[test]
fn arrays_are_mutable_objects() {
    let globals: Scope = Default::default();
    let src =
        "import numpy as np\na = np.zeros((2, 2))\nb = a\nb[0, 1] = 5.0\na[1] = [7.0, 8.0]\na[:, 0] += 1\nr = str(a)\n";
    let module = crate::syntax::parse_module(src).unwrap();
    Interp::new(globals.clone(), None).run(&module).unwrap();
    assert_eq!(globals.borrow().get("r").and_then(|v| v.as_str().map(str::to_string)).unwrap(), "[[1. 5.]\n [8. 8.]]");
}
