//! pest's parse result copied into one flat array of nodes, read by the
//! AST builder through a `Pair`-like cursor.
//!
//! Why: pest's `Pair`/`Pairs` clone two `Rc`s per pair handed out, walk the
//! children again to count them at every `into_inner`, and look up a pair's
//! end token to read its rule. The builder visits every pair once or twice,
//! so that bookkeeping was a large share of the pairs → AST step. Here the
//! token stream is read once into `RawNode`s (rule, byte range, index past
//! the subtree) and a [`Node`] is a `Copy` index into that array.

use crate::parser::Rule;
use pest::iterators::Pairs;
use pest::Token;

/// One pair of the parse: its rule, its byte range in the input, and the
/// index just past its subtree (its first child, if any, is the next node).
#[derive(Clone, Copy, Debug)]
struct RawNode {
    rule: Rule,
    start: u32,
    end: u32,
    next: u32,
}

/// All pairs of one parse, in pre-order.
pub struct Tree<'i> {
    nodes: Vec<RawNode>,
    input: &'i str,
}

impl<'i> Tree<'i> {
    /// Flatten `pairs` (spans are byte offsets into `input`, as pest's are).
    pub fn new(pairs: Pairs<'i, Rule>, input: &'i str) -> Tree<'i> {
        let tokens = pairs.tokens();
        let mut nodes = Vec::with_capacity(tokens.len() / 2);
        let mut open: Vec<usize> = Vec::with_capacity(64);
        for token in tokens {
            match token {
                Token::Start { rule, pos } => {
                    open.push(nodes.len());
                    nodes.push(RawNode {
                        rule,
                        start: pos.pos() as u32,
                        end: pos.pos() as u32,
                        next: 0,
                    });
                }
                Token::End { pos, .. } => {
                    // pest's token stream is well nested: every End closes
                    // the last open Start.
                    if let Some(i) = open.pop() {
                        let next = nodes.len() as u32;
                        let node = &mut nodes[i];
                        node.end = pos.pos() as u32;
                        node.next = next;
                    }
                }
            }
        }
        Tree { nodes, input }
    }

    /// The top-level nodes.
    pub fn top(&self) -> Children<'_> {
        Children {
            nodes: &self.nodes,
            input: self.input,
            cur: 0,
            end: self.nodes.len(),
        }
    }
}

/// One pair of the parse (cheap to copy).
#[derive(Clone, Copy)]
pub struct Node<'t> {
    nodes: &'t [RawNode],
    input: &'t str,
    idx: usize,
}

impl<'t> Node<'t> {
    fn raw(&self) -> RawNode {
        self.nodes[self.idx]
    }

    pub fn as_rule(&self) -> Rule {
        self.raw().rule
    }

    /// Byte offset of the start of the pair.
    pub fn start(&self) -> usize {
        self.raw().start as usize
    }

    /// Byte offset just past the end of the pair.
    pub fn end(&self) -> usize {
        self.raw().end as usize
    }

    pub fn as_str(&self) -> &'t str {
        let raw = self.raw();
        &self.input[raw.start as usize..raw.end as usize]
    }

    /// The direct children.
    pub fn into_inner(self) -> Children<'t> {
        Children {
            nodes: self.nodes,
            input: self.input,
            cur: self.idx + 1,
            end: self.raw().next as usize,
        }
    }
}

/// The children of a node, in order (an iterator that can also peek).
/// The default is an empty list.
#[derive(Clone, Default)]
pub struct Children<'t> {
    nodes: &'t [RawNode],
    input: &'t str,
    cur: usize,
    end: usize,
}

impl<'t> Children<'t> {
    /// The next child, without consuming it.
    pub fn peek(&self) -> Option<Node<'t>> {
        (self.cur < self.end).then_some(Node {
            nodes: self.nodes,
            input: self.input,
            idx: self.cur,
        })
    }
}

impl<'t> Iterator for Children<'t> {
    type Item = Node<'t>;

    fn next(&mut self) -> Option<Node<'t>> {
        let node = self.peek()?;
        self.cur = self.nodes[self.cur].next as usize;
        Some(node)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parser::CommParser;
    use pest::Parser as _;

    /// The flat tree has exactly pest's pairs: same rules, spans and nesting.
    fn same(pairs: Pairs<Rule>, nodes: Children) {
        let mut nodes = nodes;
        for pair in pairs {
            let Some(node) = nodes.next() else {
                panic!("missing node for {:?}", pair.as_rule());
            };
            assert_eq!(node.as_rule(), pair.as_rule());
            assert_eq!(node.start(), pair.as_span().start());
            assert_eq!(node.end(), pair.as_span().end());
            assert_eq!(node.as_str(), pair.as_str());
            same(pair.into_inner(), node.into_inner());
        }
        assert!(nodes.next().is_none(), "extra node");
    }

    #[test]
    fn flat_tree_mirrors_pest_pairs() {
        let source = "MA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\nfor i in range(3):\n    x = [a[i] + -b * 2 for a in (c, d) if a]\n";
        let marked = crate::logical::mark_line_ends(source);
        let pairs = CommParser::parse(Rule::module, &marked).expect("parses");
        let tree = Tree::new(pairs.clone(), &marked);
        same(pairs, tree.top());
    }

    #[test]
    fn peek_does_not_advance() {
        let source = "f(a, b)\n";
        let marked = crate::logical::mark_line_ends(source);
        let pairs = CommParser::parse(Rule::module, &marked).expect("parses");
        let tree = Tree::new(pairs, source);
        let mut top = tree.top();
        let first = top.peek().map(|n| n.as_rule());
        assert_eq!(top.next().map(|n| n.as_rule()), first);
    }
}
