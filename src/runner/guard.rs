//! No panic reaches the user: the runner runs the interpreter and every command's stage under
//! [`catch`], which turns a panic (a bug of aster-rs, never of the command file) into a message the
//! runner reports as a located `<F> ... internal error: ...`, and the panic hook stays silent for
//! panics caught here (no raw backtrace on the console), while panics elsewhere in the process (a
//! failing test's assertion) are reported by the hook that was there before.

use std::cell::Cell;
use std::panic::{self, AssertUnwindSafe, PanicHookInfo};
use std::sync::Once;

thread_local! {
    /// How many `catch` calls are running on this thread.
    static GUARDED: Cell<usize> = const { Cell::new(0) };
    /// What the hook saw of the last panic caught on this thread.
    static LAST: Cell<Option<String>> = const { Cell::new(None) };
}

/// The panic hook, installed once: silent (it records) under `catch`, the previous hook elsewhere.
fn install_hook() {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if GUARDED.with(Cell::get) > 0 {
                LAST.with(|l| l.set(Some(describe(info))));
            } else {
                previous(info)
            }
        }));
    });
}

/// The panic's message and where in aster-rs's source it arose.
fn describe(info: &PanicHookInfo<'_>) -> String {
    let payload = info.payload();
    let msg = payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".into());
    match info.location() {
        Some(l) => format!("{msg} (at {}:{})", l.file(), l.line()),
        None => msg,
    }
}

/// Run `f`; a panic inside it becomes `Err(message)`.
pub fn catch<R>(f: impl FnOnce() -> R) -> Result<R, String> {
    install_hook();
    GUARDED.with(|g| g.set(g.get() + 1));
    let r = panic::catch_unwind(AssertUnwindSafe(f));
    GUARDED.with(|g| g.set(g.get() - 1));
    r.map_err(|_| LAST.with(|l| l.take()).unwrap_or_else(|| "a panic".into()))
}

/// The test hook `ASTER_INJECT_PANIC=NAME`: a run panics inside the stage of command NAME, so that
/// tests can prove no panic reaches the user. Read once per run; unset in normal use.
pub fn injected_panic() -> Option<String> {
    std::env::var("ASTER_INJECT_PANIC").ok().filter(|s| !s.is_empty())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_a_message_naming_where() {
        let r: Result<(), String> = catch(|| panic!("boom {}", 42));
        let msg = r.unwrap_err();
        assert!(msg.starts_with("boom 42 (at src/runner/guard.rs:"), "{msg}");
        assert_eq!(catch(|| 7), Ok(7));
        // Nested catches unwind to the innermost.
        assert_eq!(catch(|| catch(|| -> i32 { panic!("inner") }).unwrap_err().starts_with("inner")), Ok(true));
    }
}
