//! Guard conditions (`isControllingClient(transportData) && !isDefault()`), parsed once
//! into an expression tree: calls with arguments, `!`, `&&`, `||`, parentheses and the
//! constants `true` and `false`. `&&` binds tighter than `||`.

/// A parsed guard condition.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Cond {
    /// A guard function with its arguments as written (a name, or a quoted constant).
    Call(String, Vec<String>),
    /// `true` or `false`.
    Const(bool),
    /// `!e`.
    Not(Box<Cond>),
    /// `a && b && …`.
    And(Vec<Cond>),
    /// `a || b || …`.
    Or(Vec<Cond>),
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Name(String),
    Quoted(String),
    Open,
    Close,
    Comma,
    Not,
    And,
    Or,
}

fn lex(text: &str) -> Result<Vec<Tok>, String> {
    let b: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        match c {
            c if c.is_whitespace() => i += 1,
            '(' => (out.push(Tok::Open), i += 1).1,
            ')' => (out.push(Tok::Close), i += 1).1,
            ',' => (out.push(Tok::Comma), i += 1).1,
            '!' if b.get(i + 1) != Some(&'=') => (out.push(Tok::Not), i += 1).1,
            '&' if b.get(i + 1) == Some(&'&') => (out.push(Tok::And), i += 2).1,
            '|' if b.get(i + 1) == Some(&'|') => (out.push(Tok::Or), i += 2).1,
            '\'' | '"' => {
                let end = b[i + 1..]
                    .iter()
                    .position(|&x| x == c)
                    .ok_or_else(|| format!("unterminated quote at column {}", i + 1))?;
                out.push(Tok::Quoted(b[i + 1..i + 1 + end].iter().collect()));
                i += end + 2;
            }
            c if c.is_alphanumeric() || c == '_' || c == '.' || c == '-' => {
                let start = i;
                while i < b.len() && (b[i].is_alphanumeric() || matches!(b[i], '_' | '.' | '-')) {
                    i += 1;
                }
                out.push(Tok::Name(b[start..i].iter().collect()));
            }
            _ => return Err(format!("unexpected `{c}` at column {}", i + 1)),
        }
    }
    Ok(out)
}

struct Parser {
    toks: Vec<Tok>,
    at: usize,
}

impl Parser {
    fn peek(&self) -> Option<&Tok> {
        self.toks.get(self.at)
    }
    fn next(&mut self) -> Option<Tok> {
        let t = self.toks.get(self.at).cloned();
        self.at += 1;
        t
    }
    fn or(&mut self) -> Result<Cond, String> {
        let mut v = vec![self.and()?];
        while self.peek() == Some(&Tok::Or) {
            self.at += 1;
            v.push(self.and()?);
        }
        Ok(if v.len() == 1 {
            v.remove(0)
        } else {
            Cond::Or(v)
        })
    }
    fn and(&mut self) -> Result<Cond, String> {
        let mut v = vec![self.unary()?];
        while self.peek() == Some(&Tok::And) {
            self.at += 1;
            v.push(self.unary()?);
        }
        Ok(if v.len() == 1 {
            v.remove(0)
        } else {
            Cond::And(v)
        })
    }
    fn unary(&mut self) -> Result<Cond, String> {
        match self.next() {
            Some(Tok::Not) => Ok(Cond::Not(Box::new(self.unary()?))),
            Some(Tok::Open) => {
                let e = self.or()?;
                match self.next() {
                    Some(Tok::Close) => Ok(e),
                    _ => Err("`(` without its `)`".into()),
                }
            }
            Some(Tok::Name(n)) if n == "true" || n == "false" => Ok(Cond::Const(n == "true")),
            Some(Tok::Name(n)) if n.starts_with(|c: char| c.is_alphabetic() || c == '_') => {
                let mut args = Vec::new();
                if self.peek() == Some(&Tok::Open) {
                    self.at += 1;
                    if self.peek() == Some(&Tok::Close) {
                        self.at += 1;
                        return Ok(Cond::Call(n, args));
                    }
                    loop {
                        match self.next() {
                            Some(Tok::Name(a)) => args.push(a),
                            Some(Tok::Quoted(q)) => args.push(format!("'{q}'")),
                            _ => {
                                return Err(format!(
                                    "`{n}(`: an argument is a name or a quoted constant"
                                ))
                            }
                        }
                        match self.next() {
                            Some(Tok::Comma) => continue,
                            Some(Tok::Close) => break,
                            _ => return Err(format!("`{n}(`: expected `,` or `)`")),
                        }
                    }
                }
                Ok(Cond::Call(n, args))
            }
            Some(t) => Err(format!(
                "unexpected {t:?}: expected a guard call, `!` or `(`"
            )),
            None => Err("the condition ends early".into()),
        }
    }
}

/// Parses a guard condition.
pub(crate) fn parse(text: &str) -> Result<Cond, String> {
    let mut p = Parser {
        toks: lex(text)?,
        at: 0,
    };
    let e = p.or()?;
    match p.peek() {
        None => Ok(e),
        Some(t) => Err(format!(
            "unexpected {t:?} after a complete condition (only calls, `!`, `&&`, `||` and parentheses)"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn call(n: &str, a: &[&str]) -> Cond {
        Cond::Call(n.into(), a.iter().map(|s| s.to_string()).collect())
    }

    #[test]
    fn precedence_negation_and_parentheses() {
        assert_eq!(
            parse("a(x) && !b(y) || (c())").unwrap(),
            Cond::Or(vec![
                Cond::And(vec![
                    call("a", &["x"]),
                    Cond::Not(Box::new(call("b", &["y"])))
                ]),
                call("c", &[]),
            ])
        );
        assert_eq!(
            parse("! isX( msg ) && (p || q('K'))").unwrap(),
            Cond::And(vec![
                Cond::Not(Box::new(call("isX", &["msg"]))),
                Cond::Or(vec![call("p", &[]), call("q", &["'K'"])]),
            ])
        );
        assert_eq!(parse("true").unwrap(), Cond::Const(true));
    }

    #[test]
    fn errors_say_what_is_wrong() {
        assert!(parse("a(x) &&").unwrap_err().contains("ends early"));
        assert!(parse("(a(x)").unwrap_err().contains("`)`"));
        assert!(parse("a(x) == 3").unwrap_err().contains("unexpected"));
        assert!(parse("a(x) b(y)").unwrap_err().contains("after a complete"));
    }
}
