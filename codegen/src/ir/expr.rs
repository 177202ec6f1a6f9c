//! Run-time scale expressions: `1875 / (512 * encoder_resolution)`.
//!
//! A tiny recursive-descent parser over numbers, parameter names, `+ - * /` and parentheses.

use std::fmt;

use drivebus_model::Ratio;

/// A parsed scale expression.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Expr {
    /// An exact rational literal.
    Number(Ratio),
    /// The raw value of another parameter.
    Parameter(String),
    /// Binary operation.
    Binary(Box<Expr>, Op, Box<Expr>),
    /// Unary minus.
    Negate(Box<Expr>),
    /// Placeholder before parsing.
    #[default]
    Empty,
}

/// A binary operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
}

/// Why an expression did not parse; `at` is a byte offset into the expression.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ExprError {
    /// Byte offset of the problem.
    pub at: usize,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for ExprError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} (at offset {})", self.message, self.at)
    }
}

/// Nesting deeper than this is refused so a hostile description cannot overflow the stack.
const MAX_DEPTH: usize = 32;

struct Parser<'a> {
    text: &'a str,
    pos: usize,
    depth: usize,
}

impl Expr {
    /// Parses an expression.
    pub fn parse(text: &str) -> Result<Expr, ExprError> {
        let mut parser = Parser {
            text,
            pos: 0,
            depth: 0,
        };
        let expr = parser.sum()?;
        parser.skip_space();
        if parser.pos != text.len() {
            return Err(parser.error("unexpected character"));
        }
        Ok(expr)
    }

    /// Names of the parameters the expression reads, in first-use order, without repeats.
    pub fn inputs(&self) -> Vec<String> {
        let mut names = Vec::new();
        self.collect_inputs(&mut names);
        names
    }

    fn collect_inputs(&self, names: &mut Vec<String>) {
        match self {
            Expr::Parameter(name) if !names.contains(name) => names.push(name.clone()),
            Expr::Binary(a, _, b) => {
                a.collect_inputs(names);
                b.collect_inputs(names);
            }
            Expr::Negate(a) => a.collect_inputs(names),
            _ => {}
        }
    }
}

impl Parser<'_> {
    fn error(&self, message: &str) -> ExprError {
        ExprError {
            at: self.pos,
            message: message.into(),
        }
    }

    fn skip_space(&mut self) {
        let rest = &self.text[self.pos..];
        self.pos += rest.len() - rest.trim_start().len();
    }

    fn peek(&mut self) -> Option<char> {
        self.skip_space();
        self.text[self.pos..].chars().next()
    }

    fn sum(&mut self) -> Result<Expr, ExprError> {
        let mut left = self.product()?;
        while let Some(op) = self.peek().and_then(|c| match c {
            '+' => Some(Op::Add),
            '-' => Some(Op::Sub),
            _ => None,
        }) {
            self.pos += 1;
            left = Expr::Binary(Box::new(left), op, Box::new(self.product()?));
        }
        Ok(left)
    }

    fn product(&mut self) -> Result<Expr, ExprError> {
        let mut left = self.atom()?;
        while let Some(op) = self.peek().and_then(|c| match c {
            '*' => Some(Op::Mul),
            '/' => Some(Op::Div),
            _ => None,
        }) {
            self.pos += 1;
            left = Expr::Binary(Box::new(left), op, Box::new(self.atom()?));
        }
        Ok(left)
    }

    fn atom(&mut self) -> Result<Expr, ExprError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(self.error("expression nested too deeply"));
        }
        let result = match self.peek() {
            Some('(') => {
                self.pos += 1;
                let inner = self.sum()?;
                if self.peek() != Some(')') {
                    return Err(self.error("expected `)`"));
                }
                self.pos += 1;
                Ok(inner)
            }
            Some('-') => {
                self.pos += 1;
                Ok(Expr::Negate(Box::new(self.atom()?)))
            }
            Some(c) if c.is_ascii_digit() => self.number(),
            Some(c) if c.is_ascii_alphabetic() || c == '_' => Ok(self.name()),
            Some(_) => Err(self.error("expected a number, a parameter name or `(`")),
            None => Err(self.error("expression ends too early")),
        };
        self.depth -= 1;
        result
    }

    fn take_while(&mut self, keep: impl Fn(char) -> bool) -> &str {
        let start = self.pos;
        let len: usize = self.text[start..]
            .chars()
            .take_while(|&c| keep(c))
            .map(char::len_utf8)
            .sum();
        self.pos += len;
        &self.text[start..self.pos]
    }

    fn number(&mut self) -> Result<Expr, ExprError> {
        let start = self.pos;
        let literal = self
            .take_while(|c| c.is_ascii_digit() || c == '.')
            .to_owned();
        drivebus_model::Ratio::parse_decimal(&literal)
            .map(Expr::Number)
            .ok_or(ExprError {
                at: start,
                message: format!("`{literal}` is not a number"),
            })
    }

    fn name(&mut self) -> Expr {
        Expr::Parameter(
            self.take_while(|c| c.is_ascii_alphanumeric() || c == '_')
                .to_owned(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_kinco_speed_factor() {
        let e = Expr::parse("1875 / (512 * encoder_resolution)").unwrap();
        assert_eq!(e.inputs(), vec!["encoder_resolution".to_string()]);
        assert_eq!(
            e,
            Expr::Binary(
                Box::new(Expr::Number(Ratio::int(1875))),
                Op::Div,
                Box::new(Expr::Binary(
                    Box::new(Expr::Number(Ratio::int(512))),
                    Op::Mul,
                    Box::new(Expr::Parameter("encoder_resolution".into()))
                ))
            )
        );
    }

    #[test]
    fn reports_where_it_fails() {
        assert_eq!(Expr::parse("1 + ").unwrap_err().at, 4);
        assert_eq!(Expr::parse("(1").unwrap_err().message, "expected `)`");
        assert!(Expr::parse("a; drop").is_err());
        assert!(Expr::parse(&"(".repeat(100)).is_err());
    }
}
