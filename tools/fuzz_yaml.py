"""A small YAML subset reader and writer for the fuzz harness (tools/fuzz_decks.py and its case
modules): block maps and sequences, flow [..] and {..}, anchors and aliases (expanded), comments.
Scalars keep their source text; maps are dicts, sequences lists. Enough to parse the example decks,
mutate them as trees and write them back; not a YAML implementation."""


class YamlSubsetError(Exception):
    pass


def _strip_comment(line):
    out, q = [], None
    for i, c in enumerate(line):
        if q:
            if c == q:
                q = None
        elif c in "'\"":
            q = c
        elif c == "#" and (i == 0 or line[i - 1] in " \t"):
            break
        out.append(c)
    return "".join(out).rstrip()


def _split_key(text):
    """'key: rest' -> (key, rest) at the first ': ' (or trailing ':') outside brackets/quotes."""
    depth, q = 0, None
    for i, c in enumerate(text):
        if q:
            if c == q:
                q = None
            continue
        if c in "'\"":
            q = c
        elif c in "[{":
            depth += 1
        elif c in "]}":
            depth -= 1
        elif c == ":" and depth == 0 and (i + 1 == len(text) or text[i + 1] == " "):
            return text[:i].strip(), text[i + 1:].strip()
    return None


class _Flow:
    def __init__(self, s, anchors):
        self.s, self.i, self.anchors = s, 0, anchors

    def ws(self):
        while self.i < len(self.s) and self.s[self.i] in " \t":
            self.i += 1

    def value(self, stops):
        self.ws()
        if self.i >= len(self.s):
            return ""
        c = self.s[self.i]
        if c == "[":
            self.i += 1
            out = []
            while True:
                self.ws()
                if self.s[self.i:self.i + 1] == "]":
                    self.i += 1
                    return out
                out.append(self.value(",]"))
                self.ws()
                if self.s[self.i:self.i + 1] == ",":
                    self.i += 1
                elif self.s[self.i:self.i + 1] == "]":
                    self.i += 1
                    return out
                else:
                    raise YamlSubsetError("bad flow sequence")
        if c == "{":
            self.i += 1
            out = {}
            while True:
                self.ws()
                if self.s[self.i:self.i + 1] == "}":
                    self.i += 1
                    return out
                k = self.scalar(":,}").strip()
                if self.s[self.i:self.i + 1] != ":":
                    raise YamlSubsetError("bad flow map")
                self.i += 1
                out[k] = self.value(",}")
                self.ws()
                if self.s[self.i:self.i + 1] == ",":
                    self.i += 1
                elif self.s[self.i:self.i + 1] == "}":
                    self.i += 1
                    return out
                else:
                    raise YamlSubsetError("bad flow map")
        v = self.scalar(stops).strip()
        if v.startswith("*") and v[1:] in self.anchors:
            return _copy(self.anchors[v[1:]])
        return v

    def scalar(self, stops):
        start, q = self.i, None
        while self.i < len(self.s):
            c = self.s[self.i]
            if q:
                if c == q:
                    q = None
            elif c in "'\"":
                q = c
            elif c in stops:
                break
            self.i += 1
        return self.s[start:self.i]


def _copy(node):
    if isinstance(node, dict):
        return {k: _copy(v) for k, v in node.items()}
    if isinstance(node, list):
        return [_copy(v) for v in node]
    return node


def _inline(rest, anchors):
    anchor = None
    if rest.startswith("&"):
        parts = rest.split(None, 1)
        anchor = parts[0][1:]
        rest = parts[1] if len(parts) > 1 else ""
    if rest == "":
        return anchor, None
    f = _Flow(rest, anchors)
    v = f.value("")
    if anchor:
        anchors[anchor] = v
    return anchor, v


def yaml_load(text):
    lines = []
    for raw in text.splitlines():
        s = _strip_comment(raw)
        if s.strip() == "" or s.strip() == "---":
            continue
        lines.append((len(s) - len(s.lstrip(" ")), s.strip()))
    anchors = {}
    pos = [0]

    def block(indent):
        if pos[0] >= len(lines):
            return None
        ind, content = lines[pos[0]]
        if content.startswith("- ") or content == "-":
            return seq(ind)
        return mapping(ind)

    def child(parent_indent, anchor, seq_same_indent_ok):
        if pos[0] < len(lines):
            ind, content = lines[pos[0]]
            if ind > parent_indent and content.startswith(("[", "{")):
                text = content
                pos[0] += 1
                while text.count("[") + text.count("{") > text.count("]") + text.count("}") \
                        and pos[0] < len(lines):
                    text += " " + lines[pos[0]][1]
                    pos[0] += 1
                v = _Flow(text, anchors).value("")
                if anchor:
                    anchors[anchor] = v
                return v
            if ind > parent_indent or (seq_same_indent_ok and ind == parent_indent and content.startswith("-")):
                v = block(ind)
                if anchor:
                    anchors[anchor] = v
                return v
        return ""

    def mapping(indent):
        out = {}
        while pos[0] < len(lines):
            ind, content = lines[pos[0]]
            if ind != indent or content.startswith("- "):
                break
            kv = _split_key(content)
            if kv is None:
                raise YamlSubsetError(f"not a key: {content}")
            k, rest = kv
            pos[0] += 1
            anchor, v = _inline(rest, anchors)
            out[k] = v if v is not None else child(indent, anchor, True)
        return out

    def seq(indent):
        out = []
        while pos[0] < len(lines):
            ind, content = lines[pos[0]]
            if ind != indent or not (content.startswith("- ") or content == "-"):
                break
            rest = content[1:].strip()
            if rest and not rest.startswith(("[", "{", "&", "*")) and _split_key(rest) is not None:
                # "- key: value" starts a map at indent + 2
                lines[pos[0]] = (indent + 2, rest)
                out.append(mapping(indent + 2))
                continue
            pos[0] += 1
            anchor, v = _inline(rest, anchors)
            out.append(v if v is not None else child(indent, anchor, False))
        return out

    root = block(0)
    if pos[0] != len(lines):
        raise YamlSubsetError(f"unparsed line {lines[pos[0]]}")
    return root


def _flow(node):
    if isinstance(node, dict):
        return "{" + ", ".join(f"{k}: {_flow(v)}" for k, v in node.items()) + "}"
    if isinstance(node, list):
        return "[" + ", ".join(_flow(v) for v in node) + "]"
    return node


def _is_simple(node):
    if isinstance(node, dict):
        return all(not isinstance(v, (dict, list)) for v in node.values()) and len(node) <= 8
    if isinstance(node, list):
        return all(not isinstance(v, dict) for v in node)
    return True


def yaml_dump(node, indent=0):
    pad = " " * indent
    out = []
    if isinstance(node, dict):
        for k, v in node.items():
            if isinstance(v, (dict, list)) and v and not (isinstance(v, list) and _is_simple(v)):
                out.append(f"{pad}{k}:")
                out.append(yaml_dump(v, indent + 2))
            else:
                out.append(f"{pad}{k}: {_flow(v)}")
    elif isinstance(node, list):
        for v in node:
            if isinstance(v, dict) and v and not _is_simple(v):
                sub = yaml_dump(v, indent + 2).split("\n")
                out.append(f"{pad}- {sub[0].lstrip()}")
                out.extend(sub[1:])
            else:
                out.append(f"{pad}- {_flow(v)}")
    else:
        out.append(pad + str(node))
    return "\n".join(x for x in out if x != "")


def _paths(node, prefix=()):
    """Every (path, node) in the tree, containers included, root excluded."""
    res = []
    if isinstance(node, dict):
        for k, v in node.items():
            res.append((prefix + (k,), v))
            res.extend(_paths(v, prefix + (k,)))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            res.append((prefix + (i,), v))
            res.extend(_paths(v, prefix + (i,)))
    return res


def _get(node, path):
    for p in path:
        node = node[p]
    return node


def _set(node, path, value):
    _get(node, path[:-1])[path[-1]] = value


def _delete(node, path):
    parent = _get(node, path[:-1])
    del parent[path[-1]]


def _dotted(path):
    return ".".join(str(p) for p in path)


def _is_number(s):
    if not isinstance(s, str):
        return False
    try:
        float(s)
        return True
    except ValueError:
        return False
