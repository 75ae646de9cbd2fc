"""The README's and docs/' pages, their fenced blocks and the shell commands those blocks give.

Shared by check_docs.py (the commands checked against the built programs) and run_doc_commands.py
(the commands run)."""
import os
import re
import shlex


def pages(source):
    """README.md, then every page under docs/, in a fixed order."""
    yield os.path.join(source, "README.md")
    for root, dirs, files in os.walk(os.path.join(source, "docs")):
        dirs.sort()
        for f in sorted(files):
            if f.endswith(".md"):
                yield os.path.join(root, f)


def fenced_blocks(lines):
    """(language, first line number, lines, the line before the fence) of each fenced block."""
    k = 0
    while k < len(lines):
        m = re.match(r"^\s*```(\w*)", lines[k])
        if m:
            start, body = k, []
            k += 1
            while k < len(lines) and not re.match(r"^\s*```", lines[k]):
                body.append(lines[k])
                k += 1
            before = lines[start - 1] if start > 0 else ""
            yield m.group(1), start + 2, body, before
        k += 1


def shell_commands(first, body):
    """(line number, command) of each command of a shell block: continued lines joined, trailing
    comments dropped; a here-document stays with the command that opens it."""
    joined, start, heredoc = "", first, None
    for k, l in enumerate(body):
        if heredoc is not None:
            joined += "\n" + l
            if l.strip() == heredoc:
                yield start, joined
                joined, heredoc = "", None
            continue
        if not joined:
            start = first + k
        if not l.strip() and not joined:
            continue
        joined += l[:-1] + " " if l.endswith("\\") else l
        if l.endswith("\\"):
            continue
        m = re.search(r"<<\s*'?(\w+)'?", joined)
        if m:
            heredoc = m.group(1)
            continue
        command = re.split(r"\s+#", joined, 1)[0].strip()
        joined = ""
        if command and not command.startswith("#"):
            yield start, command


def simple_commands(command):
    """The word lists of the simple commands of `command` (split at &&, ||, ; and | outside quotes),
    each with its leading VAR=value assignments removed; a command shlex cannot split is left out."""
    lexer = shlex.shlex(command.split("\n", 1)[0], posix=True, punctuation_chars=";&|")
    lexer.whitespace_split = True
    try:
        tokens = list(lexer)
    except ValueError:
        return
    words = []
    for token in tokens + [";"]:
        if token in ("&&", "||", ";", "|", "&"):
            while words and re.fullmatch(r"\w+=.*", words[0]):
                words = words[1:]
            if words:
                yield words
            words = []
        else:
            words.append(token)
