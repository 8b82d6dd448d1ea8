//! A scene file's JSON text read straight into the format's [`Value`], in one pass with
//! the nesting bounded as it reads: the loading path of the bindings, with no host-language
//! data in between. It takes plain JSON as Python's `json` reads it; what it does not take
//! (the text is not JSON, a key is given twice, nesting passes [`MAX_DEPTH`], a string holds
//! a lone surrogate, an integer needs more than 64 bits) it leaves to the binding's reader,
//! whose messages name the file and the entry as they always have.

use std::collections::HashSet;

use super::value::Value;
use super::MAX_DEPTH;

/// The data of a JSON text, or None where the text is not plain JSON this reader takes
/// (see the module's note): Python's `json.loads` then reads it, and refuses it by name.
/// Numbers read as Python reads them: an integer as an integer, the rest as the nearest
/// double; `NaN`, `Infinity` and `-Infinity` as Python's `json` takes them.
pub fn read_json(text: &str) -> Option<Value> {
    let mut r = Reader { b: text.as_bytes(), text, i: 0 };
    r.ws();
    let v = r.value(1)?;
    r.ws();
    (r.i == r.b.len()).then_some(v)
}

struct Reader<'a> {
    b: &'a [u8],
    text: &'a str,
    i: usize,
}

impl Reader<'_> {
    fn peek(&self) -> Option<u8> {
        self.b.get(self.i).copied()
    }

    /// JSON's whitespace (Python's `json` takes no other).
    fn ws(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t' | b'\n' | b'\r')) {
            self.i += 1;
        }
    }

    /// `word` next, read as `v`.
    fn word(&mut self, word: &str, v: Value) -> Option<Value> {
        self.b[self.i..].starts_with(word.as_bytes()).then(|| {
            self.i += word.len();
            v
        })
    }

    /// The value at the reader, a list or mapping at nesting `depth` (the text's own 1).
    fn value(&mut self, depth: usize) -> Option<Value> {
        match self.peek()? {
            b'{' | b'[' if depth > MAX_DEPTH => None,
            b'{' => self.object(depth),
            b'[' => self.array(depth),
            b'"' => self.string().map(Value::Str),
            b't' => self.word("true", Value::Bool(true)),
            b'f' => self.word("false", Value::Bool(false)),
            b'n' => self.word("null", Value::Null),
            b'N' => self.word("NaN", Value::Float(f64::NAN)),
            b'I' => self.word("Infinity", Value::Float(f64::INFINITY)),
            b'-' if self.b.get(self.i + 1) == Some(&b'I') => self.word("-Infinity", Value::Float(f64::NEG_INFINITY)),
            b'-' | b'0'..=b'9' => self.number(),
            _ => None,
        }
    }

    /// The items of a list or mapping (at its opening bracket) up to `close`, each read by
    /// `item` (a value, or a key and its value), separated by commas.
    fn items(&mut self, close: u8, mut item: impl FnMut(&mut Self) -> Option<()>) -> Option<()> {
        self.i += 1;
        self.ws();
        if self.peek()? == close {
            self.i += 1;
            return Some(());
        }
        loop {
            item(self)?;
            self.ws();
            match self.peek()? {
                b',' => {
                    self.i += 1;
                    self.ws();
                }
                c if c == close => {
                    self.i += 1;
                    return Some(());
                }
                _ => return None,
            }
        }
    }

    fn array(&mut self, depth: usize) -> Option<Value> {
        let mut items = Vec::new();
        self.items(b']', |r| {
            items.push(r.value(depth + 1)?);
            Some(())
        })?;
        Some(Value::List(items))
    }

    fn object(&mut self, depth: usize) -> Option<Value> {
        let mut entries = Vec::new();
        self.items(b'}', |r| {
            if r.peek()? != b'"' {
                return None;
            }
            let key = r.string()?;
            r.ws();
            if r.peek()? != b':' {
                return None;
            }
            r.i += 1;
            r.ws();
            entries.push((Value::Str(key), r.value(depth + 1)?));
            Some(())
        })?;
        (!twice(&entries)).then_some(Value::Map(entries))
    }

    /// A string (at its opening quote): control characters refused as Python's strict
    /// reader refuses them, escapes read as it reads them.
    fn string(&mut self) -> Option<String> {
        self.i += 1;
        let mut out = String::new();
        loop {
            // a run with no escape: one slice of the text (a string without escapes is one)
            let run = self.i;
            loop {
                match self.peek()? {
                    b'"' | b'\\' => break,
                    c if c < 0x20 => return None,
                    _ => self.i += 1,
                }
            }
            out.push_str(&self.text[run..self.i]);
            if self.peek()? == b'"' {
                self.i += 1;
                return Some(out);
            }
            self.i += 1;
            let c = match self.peek()? {
                b'"' => '"',
                b'\\' => '\\',
                b'/' => '/',
                b'b' => '\u{8}',
                b'f' => '\u{c}',
                b'n' => '\n',
                b'r' => '\r',
                b't' => '\t',
                b'u' => {
                    let hi = self.hex4()?;
                    match hi {
                        0xD800..=0xDBFF => {
                            // a pair; a lone half has no Rust string (Python keeps it)
                            if !self.b[self.i + 1..].starts_with(b"\\u") {
                                return None;
                            }
                            self.i += 2;
                            let lo = self.hex4()?;
                            if !(0xDC00..=0xDFFF).contains(&lo) {
                                return None;
                            }
                            char::from_u32(0x10000 + ((hi - 0xD800) << 10) + (lo - 0xDC00))?
                        }
                        _ => char::from_u32(hi)?,
                    }
                }
                _ => return None,
            };
            out.push(c);
            self.i += 1;
        }
    }

    /// The four hex digits after the `u` at the reader, which is left on the last.
    fn hex4(&mut self) -> Option<u32> {
        let digits = self.b.get(self.i + 1..self.i + 5)?;
        let mut v = 0;
        for &d in digits {
            v = v * 16 + (d as char).to_digit(16)?;
        }
        self.i += 4;
        Some(v)
    }

    fn digits(&mut self) -> usize {
        let start = self.i;
        while matches!(self.peek(), Some(b'0'..=b'9')) {
            self.i += 1;
        }
        self.i - start
    }

    /// A number as Python's `json` matches it: `-?(0|[1-9]\d*)(\.\d+)?([eE][-+]?\d+)?`, an
    /// integer without fraction or exponent.
    fn number(&mut self) -> Option<Value> {
        let start = self.i;
        if self.peek() == Some(b'-') {
            self.i += 1;
        }
        match self.peek()? {
            b'0' => self.i += 1,
            b'1'..=b'9' => {
                self.digits();
            }
            _ => return None,
        }
        let mut float = false;
        if self.peek() == Some(b'.') && matches!(self.b.get(self.i + 1), Some(b'0'..=b'9')) {
            self.i += 1;
            self.digits();
            float = true;
        }
        if matches!(self.peek(), Some(b'e' | b'E')) {
            let mark = self.i;
            self.i += 1;
            if matches!(self.peek(), Some(b'+' | b'-')) {
                self.i += 1;
            }
            if self.digits() == 0 {
                self.i = mark; // not an exponent: the number ends before it
            } else {
                float = true;
            }
        }
        let s = &self.text[start..self.i];
        if float {
            s.parse().ok().map(Value::Float)
        } else {
            s.parse().ok().map(Value::Int)
        }
    }
}

/// Whether a key is given twice in `entries` (all string keys).
fn twice(entries: &[(Value, Value)]) -> bool {
    fn key(e: &(Value, Value)) -> Option<&str> {
        e.0.as_str()
    }
    if entries.len() <= 8 {
        return entries.iter().enumerate().any(|(i, a)| entries[..i].iter().any(|b| key(a) == key(b)));
    }
    let mut seen = HashSet::with_capacity(entries.len());
    !entries.iter().all(|e| seen.insert(key(e)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Python's `repr(json.loads(text))`, as Python prints it.
    fn read(text: &str) -> String {
        read_json(text).expect("plain JSON").repr()
    }

    #[test]
    fn reads_what_python_reads() {
        let text = " {\"a\": [1, -0, 2.5, -1e-5, 1E400, \"x\", null, true, false],\n\t\"b\": {}, \"c\": []} ";
        assert_eq!(read(text), "{'a': [1, 0, 2.5, -1e-05, inf, 'x', None, True, False], 'b': {}, 'c': []}");
        assert_eq!(read("[NaN, Infinity, -Infinity]"), "[nan, inf, -inf]");
        assert_eq!(read("[0.1, 9007199254740993.0, 5e-324, 1e-400]"), "[0.1, 9007199254740992.0, 5e-324, 0.0]");
        assert_eq!(read("9223372036854775807"), "9223372036854775807");
        assert_eq!(read(r#""\"\\\/\b\f\n\r\t\u00e9\u20AC\ud83d\ude00 é""#), r#"'"\\/\x08\x0c\n\r\té€😀 é'"#);
    }

    #[test]
    fn nesting_to_the_limit_is_read() {
        let deep = |n: usize| format!("{}{}", "[".repeat(n), "]".repeat(n));
        assert!(read_json(&deep(MAX_DEPTH)).is_some());
        assert!(read_json(&format!("{{\"a\": {}}}", deep(MAX_DEPTH - 1))).is_some());
        assert!(read_json(&deep(MAX_DEPTH + 1)).is_none());
        assert!(read_json(&format!("{{\"a\": {}}}", deep(MAX_DEPTH))).is_none());
        // far past the limit: no recursion runs away
        assert!(read_json(&deep(1_000_000)).is_none());
    }

    #[test]
    fn leaves_the_rest_to_python() {
        for text in [
            "",
            " ",
            "\u{feff}{}",
            "{\"a\": 1, \"a\": 2}",
            "{\"p0\": 0, \"p1\": 1, \"p2\": 2, \"p3\": 3, \"p4\": 4, \"p5\": 5, \"p6\": 6, \"p7\": 7, \"p8\": 8, \"p3\": 9}",
            "[1,]",
            "{\"a\": 1,}",
            "{a: 1}",
            "{\"a\" 1}",
            "[1 2]",
            "{} {}",
            "01",
            "1.",
            ".5",
            "+1",
            "-",
            "1e",
            "1.5e+",
            "[1e]",
            "nul",
            "True",
            "-Inf",
            "9223372036854775808",
            "\"a\tb\"",
            "\"\\ud83d\"",
            "\"\\ude00\"",
            "\"\\ud83d\\u0041\"",
            "\"\\x41\"",
            "\"\\u00g1\"",
            "\"abc",
            "[\"a\\",
        ] {
            assert!(read_json(text).is_none(), "{text:?} is read");
        }
    }
}
