#!/usr/bin/env python3
"""Checks that every figure in the README and in docs/**/*.md has a committed source.

    check_figures.py SOURCE_DIR

A figure is a number in prose: two or more significant digits, or in exponent form ("7.2e-8"),
or a mantissa times a power of ten ("2·10⁻¹⁵", "5×10^-13"). Not figures: numbers in fenced code
blocks and in `code` (but a printed value in code, `theta_ddot(0) = 0.470316`, after "= ", is
one), the chapter's equation numbers "(5.79)", "(5.74–5.76)", "(5.94, 5.100)", citation years
("Jorba–Zou 2005"), link targets, a bare power of ten ("10^7", "10⁶": an input), and the value of
a tolerance or step ("rtol 1e-10", "step 0.01": an input).

A figure is found when some number in bench/results/ rounds to it at the text's precision:
"7.2e-8" is found by 7.16e-08 or 7.2e-08, "1,070" by 1070. Each paragraph (or table) is held to
the results files it names (`bench/results/X.md`), or, naming none, to those of the paragraph
before it under the same heading; a paragraph with no named source before it under its heading
is held to all of bench/results/. A paragraph whose bold title says "estimate" does arithmetic on
measured figures and is not checked (it names its inputs' file). A paragraph that names no
results file, or not all it draws on, is on HELD_TO below with the file named there.

A figure that no committed file can hold is on ALLOWED below, with the reason (an entry that
matches nothing any more is named, to be removed). Ranges an option takes ("1 to 64") are inputs.

Prints each figure without a source with its file and line and exits 1; exits 0 when all are found.
"""
import bisect
import math
import pathlib
import re
import sys

NUMBER = re.compile(r"(?<![\w.^])(\d[\d,]*(?:\.\d+)?(?:e[-+]?\d+)?)(?![\w^⁰¹²³⁴⁵⁶⁷⁸⁹])")
SUPERSCRIPT = str.maketrans("⁻⁺⁰¹²³⁴⁵⁶⁷⁸⁹", "-+0123456789")
# "2·10⁻¹⁵", "5×10^-13", "3 x 10^4": the figure 2e-15, 5e-13, 3e4
TIMES_POWER = re.compile(r"(?<![\w.])(\d+(?:\.\d+)?)\s*[·×]\s*10(?:\^\{?([-+]?\d+)\}?|([⁻⁺]?[⁰¹²³⁴⁵⁶⁷⁸⁹]+))")
PRINTED_IN_CODE = re.compile(r"= (-?\d[\d.]*(?:e[-+]?\d+)?)")
NOT_FIGURES = [re.compile(r"\(\d+\.\d+\)"),                      # the chapter's equation numbers
               re.compile(r"(?:(?<=\()|(?<=, )|(?<=–))5\.\d{1,3}(?=[–,)]|\s+for\b)"),  # (5.74–5.76)
               re.compile(r"[A-Z][a-z]+ (19|20)\d\d"),           # citations
               re.compile(r"\]\([^)]*\)"),                       # link targets
               re.compile(r"\b(?:rtol|atol|tol|tolerance|step)\s*[=:]?\s*[\d.]+(?:e[-+]?\d+)?"),
               re.compile(r"[\d.]+\s*[·×]\s*\d+\^\d+"),             # constants: 1.5 · 2^52
               re.compile(r"(?<![\d.])1 to [\d,]+\b"),                 # what an option takes: 1 to 64
               re.compile(r"(?<![\d.])[A-Za-z]\w*-\d+")]             # names: AVX-512, x86-64

# (a phrase of the paragraph, the figures it may state without a source, why). Checked as text
# moves between the README and docs/: an entry is matched by its phrase in any file.
ALLOWED = [
    ("Estrin's tree rounds more than split Horner's", ["3.8", "2.3", "1.9e-15", "4.6e-15", "19",
                                                       "1.5e-15", "4.0e-15"],
     "one-off standalone experiments (Estrin's scheme against split Horner) with a program that "
     "is not committed"),
    ("opens paused at t = 2.5", ["2.5"], "an example time in a page's address: an input"),
    ("about 24 bytes a number", ["24"], "the sweep's own estimate per number: a constant of the code"),
    ("at most about 32 MB of results wait", ["32"], "a limit set in the code, not a measurement"),
    ("HDF5 keeps attributes under 64 KiB", ["64"], "HDF5's limit, a fact of the library"),
    ("1e6 + 5·10^-7", ["5e-7"], "the scene's input: I3 - I2"),
    ("moved from 0.074 to 0.086 s", ["0.074", "0.086", "0.0744", "0.0745", "0.0408", "0.0410"],
     "one-off timings of the shared machine's noise and of two changes that measured nothing and "
     "were not kept: no committed code is left to rerun"),
    ("16 ranks 8.4×", ["8.4"],
     "a pitfall's history, measured with MPI on a 16-core machine lent to an earlier session: the "
     "chunk sizing measured was replaced (it matched a number of another file by chance before)"),
    ("1,350 instructions a dense output", ["1,350", "100", "84", "18", "12", "101"],
     "a pitfall's history: the code measured was replaced"),
    ("moves nothing (long double steps err by", ["2e-17", "3.2e-17", "1.8e-15", "1.2e-15",
                                                  "4.9e-15", "5.9e-15", "9.2e-16", "2.4e-15"],
     "a one-off experiment on e4d1780 with a copy of the stepper that is not committed (said there)"),
    ("73 of 1,971 messages", ["1,971", "98", "689", "6,716", "2,234"],
     "counts from one perf session of the nap's history on 2 cores, for code since changed"),
]


# (a phrase of a paragraph, a results file its figures come from that it does not name): the
# paragraph is held to that file too, or to it alone if it names none (better: the text names
# it, and the entry goes).
HELD_TO = [
    ("agrees to about 14 digits", "lanes_agreement.md"),
    ("The fall takes", "falling_top.md"),
    ("It prints `theta_ddot(0) =", "readme_examples.md"),
    ("A run that hits `max_steps`", "readme_examples.md"),
    ("a run there and back at the same step returns to its start", "backward.md"),
]


def result_numbers(paths):
    values = set()
    for path in paths:
        text = re.sub(r"(\d)x\b", r"\1 ", path.read_text(errors="replace"))  # "1.5x"
        for m in NUMBER.finditer(text):
            values.add(float(m.group(1).replace(",", "")))
    return sorted(v for v in values if v > 0)


def significant_digits(token):
    mantissa = token.split("e")[0]
    digits = mantissa.replace(".", "").lstrip("0")
    return len(digits) if "." in mantissa else max(len(digits.rstrip("0")), 1)


def has_source(token, values):
    if token.endswith("%"):  # "59%" is found by 59 or 0.59
        return has_source(token[:-1], values) or has_source(f"{float(token[:-1]) / 100:.{significant_digits(token[:-1]) - 1}e}", values)
    x = float(token)
    exponent = math.floor(math.log10(x))
    half = 0.5 * 10 ** (exponent - significant_digits(token) + 1) * (1 + 1e-9)
    i = bisect.bisect_left(values, x - half)
    return i < len(values) and values[i] <= x + half


def blank(m):
    return re.sub(r"[^\n]", " ", m.group())


def prose(block):
    """The block with code spans blanked but their printed values ("= 0.47") kept."""
    def code(m):
        kept = " ".join(v.group(1) for v in PRINTED_IN_CODE.finditer(m.group()))
        return kept + blank(m)[len(kept):] if len(kept) < len(m.group()) else blank(m)
    return re.sub(r"`[^`]*`", code, block)


def figures(block):
    """(token, line number in the block, line) of each figure of the block."""
    for i, (raw, line) in enumerate(zip(block.splitlines(), prose(block).splitlines())):
        if raw.startswith("|") and "`bash" in raw:  # a table of scripts
            continue
        text = line
        for m in TIMES_POWER.finditer(line):
            power = m.group(2) or m.group(3).translate(SUPERSCRIPT)
            yield f"{m.group(1)}e{int(power)}", i, raw
        text = TIMES_POWER.sub(blank, text)
        for pattern in NOT_FIGURES:
            text = pattern.sub(blank, text)
        for m in NUMBER.finditer(text):
            token = m.group(1).replace(",", "") + ("%" if text[m.end():m.end() + 1] == "%" else "")
            if float(token.rstrip("%")) > 0 and (significant_digits(token.rstrip("%")) >= 2 or "e" in token):
                yield token, i, raw


def blocks_with_sources(text, results):
    """(block, first line, the results files it is held to) for each paragraph or table."""
    sources, everything = [], sorted(p for p in results.rglob("*") if p.is_file())
    text = re.sub(r"```.*?```", blank, text, flags=re.S)  # examples, not figures
    for m in re.finditer(r"(?:[^\n]*\S[^\n]*(?:\n|$))+", text):
        block, first = m.group(), 1 + text.count("\n", 0, m.start())
        if block.startswith("#"):
            sources = []
            continue
        named = [results / n for n in re.findall(r"bench/results/([\w.]+)", block)]
        if named and not block.startswith("| figures"):
            sources = named
        held = [results / f for phrase, f in HELD_TO if phrase in " ".join(block.split())]
        if not re.match(r"\*\*[^*]*estimate", block):
            yield block, first, (held + named if held else sources) or everything


def allowed(block, token):
    for phrase, tokens, _ in ALLOWED:
        if phrase in " ".join(block.split()) and token in [t.replace(",", "") for t in tokens]:
            return phrase
    return None


def pages(root):
    return [root / "README.md", *sorted((root / "docs").rglob("*.md"))]


def main():
    root = pathlib.Path(sys.argv[1])
    results = root / "bench" / "results"
    checked, missing, used = 0, 0, set()
    for page in pages(root):
        name = page.relative_to(root)
        for block, first, sources in blocks_with_sources(page.read_text(), results):
            for absent in [s for s in sources if not s.is_file()]:
                missing += 1
                print(f"{name}:{first}: the source {absent.relative_to(root)} does not exist")
            values = result_numbers(s for s in sources if s.is_file())
            for token, i, line in figures(block):
                checked += 1
                if has_source(token, values):
                    continue
                phrase = allowed(block, token)
                if phrase:
                    used.add(phrase)
                    continue
                missing += 1
                at = first + i
                names = ", ".join(s.name for s in sources) if len(sources) < 4 else "bench/results/"
                print(f"{name}:{at}: {token} is in none of {names}: {line.strip()[:100]}")
    text = " ".join(" ".join(page.read_text().split()) for page in pages(root))
    for phrase, _ in HELD_TO:
        if phrase not in text:
            missing += 1
            print(f"check_figures.py: the HELD_TO entry '{phrase}' matches no paragraph any more")
    for phrase, _, _ in ALLOWED:  # a note only: text moves between pages while others edit it
        if phrase not in used:
            print(f"note: the allowed entry '{phrase}' matches no figure any more (remove it)")
    print(f"{checked - missing} of {checked} figures found in their sources (README.md, docs/)")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
