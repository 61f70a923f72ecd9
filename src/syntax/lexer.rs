//! Logical lines: the one pass the pest grammar cannot express.
//!
//! Python joins physical lines inside brackets and after a backslash, and its
//! comments run to the end of the line. [`logical_lines`] blanks comments and
//! turns those joining newlines into spaces, byte for byte, so every offset in
//! the result is an offset in the original text and error positions need no
//! mapping.

/// Blank comments and fold bracketed / backslash-continued newlines into spaces.
pub fn logical_lines(src: &str) -> String {
    let bytes = src.as_bytes();
    let mut out = bytes.to_vec();
    let mut depth: usize = 0;
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        match c {
            b'#' => {
                while i < bytes.len() && bytes[i] != b'\n' && bytes[i] != b'\r' {
                    out[i] = b' ';
                    i += 1;
                }
                continue;
            }
            b'\'' | b'"' => {
                i = skip_string(bytes, i);
                continue;
            }
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' | b'}' => depth = depth.saturating_sub(1),
            b'\\' => {
                // Line continuation: backslash, optional CR, LF.
                let mut j = i + 1;
                if j < bytes.len() && bytes[j] == b'\r' {
                    j += 1;
                }
                if j < bytes.len() && bytes[j] == b'\n' {
                    for o in &mut out[i..=j] {
                        *o = b' ';
                    }
                    i = j + 1;
                    continue;
                }
            }
            b'\n' | b'\r' if depth > 0 => out[i] = b' ',
            _ => {}
        }
        i += 1;
    }
    // Only ASCII bytes were replaced by ASCII spaces, so the text stays UTF-8.
    String::from_utf8(out).expect("logical_lines keeps UTF-8 intact")
}

/// The offset of the first bracket nested deeper than `limit`, if any. The
/// parser and the interpreter recurse on nesting, so it is bounded, as in Python.
pub fn too_deep(src: &str, limit: usize) -> Option<usize> {
    let bytes = src.as_bytes();
    let mut depth = 0usize;
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'#' => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            b'\'' | b'"' => {
                i = skip_string(bytes, i);
                continue;
            }
            b'(' | b'[' | b'{' => {
                depth += 1;
                if depth > limit {
                    return Some(i);
                }
            }
            b')' | b']' | b'}' => depth = depth.saturating_sub(1),
            _ => {}
        }
        i += 1;
    }
    None
}

/// The offset of the innermost bracket opened before `upto` and not closed
/// by then (strings and comments skipped), if any.
pub fn unclosed_bracket(src: &str, upto: usize) -> Option<usize> {
    let bytes = src.as_bytes();
    let upto = upto.min(bytes.len());
    let mut stack = Vec::new();
    let mut i = 0;
    while i < upto {
        match bytes[i] {
            b'#' => {
                while i < upto && bytes[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            b'\'' | b'"' => {
                i = skip_string(bytes, i);
                continue;
            }
            b'(' | b'[' | b'{' => stack.push(i),
            b')' | b']' | b'}' => {
                stack.pop();
            }
            _ => {}
        }
        i += 1;
    }
    stack.pop()
}

/// Index just past the string literal starting at `start` (a quote), or the end
/// of the line / text when it is unterminated (the grammar reports it then).
fn skip_string(bytes: &[u8], start: usize) -> usize {
    let q = bytes[start];
    let triple = bytes.len() >= start + 3 && bytes[start + 1] == q && bytes[start + 2] == q;
    let mut i = start + if triple { 3 } else { 1 };
    while i < bytes.len() {
        let c = bytes[i];
        if c == b'\\' {
            i += 2;
            continue;
        }
        if triple {
            if c == q && i + 2 < bytes.len() && bytes[i + 1] == q && bytes[i + 2] == q {
                return i + 3;
            }
        } else if c == q {
            return i + 1;
        } else if c == b'\n' {
            return i;
        }
        i += 1;
    }
    bytes.len()
}

/// 1-based line and column (in characters) of a byte offset.
pub fn line_col(src: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(src.len());
    let before = &src[..floor_char_boundary(src, offset)];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map(|p| p + 1).unwrap_or(0);
    let col = before[line_start..].chars().count() + 1;
    (line, col)
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folds_brackets_and_blanks_comments() {
        let src = "A = F(1,  # one\n      2)\nB = 3 \\\n  + 4\n";
        let out = logical_lines(src);
        assert_eq!(out.len(), src.len());
        assert_eq!(out.lines().count(), 2);
        assert!(!out.contains('#'));
        assert!(out.starts_with("A = F(1,"));
    }

    #[test]
    fn strings_are_left_alone() {
        let src = "S = '# not a comment (' ; T = \"\"\"a\n)b\"\"\"\nU = 1\n";
        let out = logical_lines(src);
        assert!(out.contains("'# not a comment ('"));
        assert!(out.contains("\"\"\"a\n)b\"\"\""));
        assert_eq!(out.lines().count(), 3);
    }

    #[test]
    fn line_col_counts_characters() {
        let src = "é = 1\nabc";
        assert_eq!(line_col(src, 0), (1, 1));
        assert_eq!(line_col(src, src.find('=').unwrap()), (1, 3));
        assert_eq!(line_col(src, src.find('b').unwrap()), (2, 2));
    }
}
