//! Test support: models written as short text instead of hand-built syntax trees.
//!
//! One item per line: `params m = 1, g`, `states x, y`, `let k = expr`,
//! `eq LABEL: lhs = rhs`, `out name = expr`, `variant NAME keep a, b fix m = 1`. Expressions
//! follow the DSL's grammar (`^` right-associative and binding tighter than unary minus).

use crate::spec::{Ast, BinOp, EquationSpec, Func, ModelSpec, Named, NodeId, VariantSpec};

struct Parser<'a> {
    chars: Vec<char>,
    pos: usize,
    next_id: &'a mut u32,
}

impl Parser<'_> {
    fn id(&mut self) -> NodeId {
        *self.next_id += 1;
        NodeId(*self.next_id)
    }

    fn skip(&mut self) {
        while self.chars.get(self.pos).is_some_and(|c| c.is_whitespace()) {
            self.pos += 1;
        }
    }

    fn eat(&mut self, c: char) -> bool {
        self.skip();
        if self.chars.get(self.pos) == Some(&c) {
            self.pos += 1;
            true
        } else {
            false
        }
    }

    fn sum(&mut self) -> Ast {
        let mut lhs = self.product();
        loop {
            let op = if self.eat('+') {
                BinOp::Add
            } else if self.eat('-') {
                BinOp::Sub
            } else {
                return lhs;
            };
            let rhs = self.product();
            lhs = Ast::Bin(self.id(), op, Box::new(lhs), Box::new(rhs));
        }
    }

    fn product(&mut self) -> Ast {
        let mut lhs = self.unary();
        loop {
            let op = if self.eat('*') {
                BinOp::Mul
            } else if self.eat('/') {
                BinOp::Div
            } else {
                return lhs;
            };
            let rhs = self.unary();
            lhs = Ast::Bin(self.id(), op, Box::new(lhs), Box::new(rhs));
        }
    }

    fn unary(&mut self) -> Ast {
        if self.eat('-') {
            let inner = self.unary();
            return Ast::Neg(self.id(), Box::new(inner));
        }
        self.power()
    }

    fn power(&mut self) -> Ast {
        let base = self.atom();
        if self.eat('^') {
            let exp = self.unary();
            return Ast::Bin(self.id(), BinOp::Pow, Box::new(base), Box::new(exp));
        }
        base
    }

    fn atom(&mut self) -> Ast {
        self.skip();
        if self.eat('(') {
            let e = self.sum();
            assert!(self.eat(')'), "expected `)`");
            return e;
        }
        let start = self.pos;
        let c = self.chars[self.pos];
        if c.is_ascii_digit() || c == '.' {
            while self
                .chars
                .get(self.pos)
                .is_some_and(|c| c.is_ascii_digit() || *c == '.' || *c == 'e')
            {
                self.pos += 1;
            }
            let text: String = self.chars[start..self.pos].iter().collect();
            return Ast::Num(self.id(), text.parse().expect("number"));
        }
        while self
            .chars
            .get(self.pos)
            .is_some_and(|c| c.is_alphanumeric() || *c == '_')
        {
            self.pos += 1;
        }
        let name: String = self.chars[start..self.pos].iter().collect();
        assert!(!name.is_empty(), "unexpected character {c:?}");
        if self.eat('(') {
            let mut args = vec![self.sum()];
            while self.eat(',') {
                args.push(self.sum());
            }
            assert!(self.eat(')'), "expected `)`");
            if name == "der" {
                let inner = args.remove(0);
                return Ast::Der(self.id(), Box::new(inner));
            }
            let f = Func::from_name(&name).expect("function");
            return Ast::Call(self.id(), f, args);
        }
        Ast::Name(self.id(), name)
    }
}

/// Parses one expression, numbering nodes from `next_id`.
pub fn expr(text: &str, next_id: &mut u32) -> Ast {
    let mut p = Parser {
        chars: text.chars().collect(),
        pos: 0,
        next_id,
    };
    let e = p.sum();
    p.skip();
    assert_eq!(p.pos, p.chars.len(), "trailing input in {text:?}");
    e
}

fn named<T>(name: &str, value: T, next_id: &mut u32) -> Named<T> {
    *next_id += 1;
    Named {
        name: name.trim().to_string(),
        id: NodeId(*next_id),
        value,
    }
}

fn list(text: &str) -> Vec<&str> {
    text.split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .collect()
}

/// Parses a model written one item per line (see the module docs).
pub fn model(text: &str) -> ModelSpec {
    let mut id = 0u32;
    let mut spec = ModelSpec {
        name: "test_model".into(),
        params: vec![],
        states: vec![],
        lets: vec![],
        equations: vec![],
        outputs: vec![],
        variants: vec![],
    };
    for line in text.lines().map(str::trim).filter(|l| !l.is_empty()) {
        let (head, rest) = line.split_once(' ').unwrap_or((line, ""));
        match head {
            "params" => {
                for p in list(rest) {
                    let (name, value) = match p.split_once('=') {
                        Some((n, v)) => (n, Some(v.trim().parse().expect("default"))),
                        None => (p, None),
                    };
                    spec.params.push(named(name, value, &mut id));
                }
            }
            "states" => {
                for s in list(rest) {
                    spec.states.push(named(s, (), &mut id));
                }
            }
            "let" | "out" => {
                let (name, e) = rest.split_once('=').expect("`=`");
                let n = named(name, (), &mut id);
                let value = expr(e, &mut id);
                let item = Named {
                    name: n.name,
                    id: n.id,
                    value,
                };
                if head == "let" {
                    spec.lets.push(item);
                } else {
                    spec.outputs.push(item);
                }
            }
            "eq" => {
                let (label, body) = rest.split_once(':').expect("`label:`");
                let (lhs, rhs) = body.split_once('=').expect("`=`");
                id += 1;
                let eq_id = NodeId(id);
                spec.equations.push(EquationSpec {
                    label: label.trim().into(),
                    id: eq_id,
                    lhs: expr(lhs, &mut id),
                    rhs: expr(rhs, &mut id),
                });
            }
            "variant" => {
                let (name, rest) = rest.split_once(' ').expect("variant name");
                let rest = rest.trim().strip_prefix("keep").expect("`keep`");
                let (keep, fix) = match rest.split_once("fix") {
                    Some((k, f)) => (k, f),
                    None => (rest, ""),
                };
                let v = named(name, (), &mut id);
                spec.variants.push(VariantSpec {
                    name: v.name,
                    id: v.id,
                    keep: list(keep)
                        .into_iter()
                        .map(|k| named(k, (), &mut id))
                        .collect(),
                    fix: list(fix)
                        .into_iter()
                        .map(|f| {
                            let (n, v) = f.split_once('=').expect("`=`");
                            named(n, v.trim().parse().expect("value"), &mut id)
                        })
                        .collect(),
                });
            }
            other => panic!("unknown item {other:?}"),
        }
    }
    spec
}
