//! Constant expressions where JSIDL wants a number (`real_upper_limit=
//! "3.14159265358979323846/2"`, `"-8*basicConsts.PI"`): numbers, constant names,
//! unary minus and plus, `+ - * /` with the usual precedence, and parentheses. Nothing
//! else is evaluated. Constant names are looked up by the caller.

/// A parsed constant expression.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Expr {
    /// A number.
    Num(f64),
    /// A constant's name (`basicConsts.PI`).
    Name(String),
    /// `-x`.
    Neg(Box<Expr>),
    /// `a op b`, op one of `+ - * /`.
    Bin(char, Box<Expr>, Box<Expr>),
}

impl Expr {
    /// True for a plain number or a name, possibly negated: what was taken before
    /// expressions were.
    pub fn is_simple(&self) -> bool {
        match self {
            Expr::Num(_) | Expr::Name(_) => true,
            Expr::Neg(e) => matches!(**e, Expr::Num(_) | Expr::Name(_)),
            Expr::Bin(..) => false,
        }
    }

    /// The value, each name's value given by `name` (or its error).
    pub fn eval<E>(&self, name: &mut impl FnMut(&str) -> Result<f64, E>) -> Result<f64, Eval<E>> {
        Ok(match self {
            Expr::Num(x) => *x,
            Expr::Name(n) => name(n).map_err(Eval::Name)?,
            Expr::Neg(e) => -e.eval(name)?,
            Expr::Bin(op, a, b) => {
                let (a, b) = (a.eval(name)?, b.eval(name)?);
                let v = match op {
                    '+' => a + b,
                    '-' => a - b,
                    '*' => a * b,
                    _ => {
                        if b == 0.0 {
                            return Err(Eval::Math("a division by zero".into()));
                        }
                        a / b
                    }
                };
                if !v.is_finite() {
                    return Err(Eval::Math("a value out of range".into()));
                }
                v
            }
        })
    }
}

/// Why an expression has no value.
#[derive(Debug)]
pub(crate) enum Eval<E> {
    /// A name did not give a number.
    Name(E),
    /// The arithmetic failed.
    Math(String),
}

/// Parses `text` as a whole, or says what is wrong with it.
pub(crate) fn parse(text: &str) -> Result<Expr, String> {
    let toks = tokens(text)?;
    let mut p = Parser { toks, i: 0 };
    let e = p.sum()?;
    match p.toks.get(p.i) {
        None => Ok(e),
        Some(t) => Err(format!("unexpected `{}`", t.show())),
    }
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Num(f64),
    Name(String),
    Op(char),
}

impl Tok {
    fn show(&self) -> String {
        match self {
            Tok::Num(x) => x.to_string(),
            Tok::Name(n) => n.clone(),
            Tok::Op(c) => c.to_string(),
        }
    }
}

fn tokens(text: &str) -> Result<Vec<Tok>, String> {
    let cs: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < cs.len() {
        let c = cs[i];
        if c.is_whitespace() {
            i += 1;
        } else if matches!(c, '+' | '-' | '*' | '/' | '(' | ')') {
            out.push(Tok::Op(c));
            i += 1;
        } else if c.is_ascii_digit() || c == '.' {
            let start = i;
            while i < cs.len() && (cs[i].is_ascii_digit() || cs[i] == '.') {
                i += 1;
            }
            // An exponent: 1e-3, 2.5E+6.
            if i < cs.len() && matches!(cs[i], 'e' | 'E') {
                let mut j = i + 1;
                if j < cs.len() && matches!(cs[j], '+' | '-') {
                    j += 1;
                }
                if j < cs.len() && cs[j].is_ascii_digit() {
                    i = j;
                    while i < cs.len() && cs[i].is_ascii_digit() {
                        i += 1;
                    }
                }
            }
            let s: String = cs[start..i].iter().collect();
            let x = s
                .parse::<f64>()
                .map_err(|_| format!("`{s}` is not a number"))?;
            out.push(Tok::Num(x));
        } else if c.is_ascii_alphabetic() || c == '_' {
            let start = i;
            while i < cs.len() && (cs[i].is_ascii_alphanumeric() || cs[i] == '_' || cs[i] == '.') {
                i += 1;
            }
            out.push(Tok::Name(cs[start..i].iter().collect()));
        } else {
            return Err(format!("`{c}` is not part of a constant expression"));
        }
    }
    Ok(out)
}

/// Recursive descent: sum := product (('+'|'-') product)*; product := unary (('*'|'/')
/// unary)*; unary := ('-'|'+') unary | atom; atom := number | name | '(' sum ')'.
struct Parser {
    toks: Vec<Tok>,
    i: usize,
}

/// How deep parentheses and signs may nest.
const MAX_DEPTH: usize = 64;

impl Parser {
    fn op(&mut self, ops: &[char]) -> Option<char> {
        match self.toks.get(self.i) {
            Some(Tok::Op(c)) if ops.contains(c) => {
                self.i += 1;
                Some(*c)
            }
            _ => None,
        }
    }

    fn sum(&mut self) -> Result<Expr, String> {
        self.sum_at(0)
    }

    fn sum_at(&mut self, depth: usize) -> Result<Expr, String> {
        let mut e = self.product(depth)?;
        while let Some(op) = self.op(&['+', '-']) {
            e = Expr::Bin(op, Box::new(e), Box::new(self.product(depth)?));
        }
        Ok(e)
    }

    fn product(&mut self, depth: usize) -> Result<Expr, String> {
        let mut e = self.unary(depth)?;
        while let Some(op) = self.op(&['*', '/']) {
            e = Expr::Bin(op, Box::new(e), Box::new(self.unary(depth)?));
        }
        Ok(e)
    }

    fn unary(&mut self, depth: usize) -> Result<Expr, String> {
        if depth > MAX_DEPTH {
            return Err("nested too deeply".into());
        }
        match self.op(&['-', '+']) {
            Some('-') => Ok(Expr::Neg(Box::new(self.unary(depth + 1)?))),
            Some(_) => self.unary(depth + 1),
            None => self.atom(depth),
        }
    }

    fn atom(&mut self, depth: usize) -> Result<Expr, String> {
        let t = self.toks.get(self.i).cloned();
        self.i += 1;
        match t {
            Some(Tok::Num(x)) => Ok(Expr::Num(x)),
            Some(Tok::Name(n)) => Ok(Expr::Name(n)),
            Some(Tok::Op('(')) => {
                let e = self.sum_at(depth + 1)?;
                match self.op(&[')']) {
                    Some(_) => Ok(e),
                    None => Err("a `(` is not closed".into()),
                }
            }
            Some(t) => Err(format!("unexpected `{}`", t.show())),
            None => Err("the expression ends early".into()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(text: &str) -> f64 {
        let e = parse(text).unwrap();
        e.eval(&mut |n: &str| match n {
            "consts.PI" => Ok(std::f64::consts::PI),
            _ => Err(()),
        })
        .unwrap()
    }

    #[test]
    fn values() {
        assert_eq!(
            value("3.14159265358979323846/2"),
            std::f64::consts::FRAC_PI_2
        );
        assert_eq!(value("-3.14159265358979323846"), -std::f64::consts::PI);
        assert_eq!(value("-8*consts.PI"), -8.0 * std::f64::consts::PI);
        assert_eq!(value("(1 + 2) * -(3 - 1) / 4"), -1.5);
        assert_eq!(value("2 - 3 - 4"), -5.0);
        assert_eq!(value("1e3 / 2.5E+1"), 40.0);
        assert!(parse("-1").unwrap().is_simple());
        assert!(parse("consts.PI").unwrap().is_simple());
        assert!(!parse("1/2").unwrap().is_simple());
    }

    #[test]
    fn refused() {
        for bad in ["", "1 +", "(1", "1)", "2^3", "f(1)", "1 2", "--", "1..2"] {
            assert!(parse(bad).is_err(), "{bad}");
        }
        let e = parse("1/0").unwrap();
        assert!(e.eval(&mut |_: &str| Err::<f64, ()>(())).is_err());
        let deep = format!("{}1{}", "(".repeat(100), ")".repeat(100));
        assert!(parse(&deep).is_err());
    }
}
