#!/usr/bin/env python3
"""Checks that every figure in the README's performance sections has a committed source.

    check_figures.py SOURCE_DIR

The sections from "## Choosing an integrator" up to "## Known limits" state measured figures; each
must come from a file under bench/results/ (the README names the script that writes it). A figure
is any number of two or more significant digits, or in exponent form, outside `code`, equation
numbers "(5.79)" and citation years ("Jorba–Zou 2005"). It is found when some number in
bench/results/ rounds to it at the README's precision: "7.2e-8" is found by 7.16e-08 or 7.2e-08,
"1,070" by 1070. A number written as a power ("10^7", "10⁶") is an input, not a figure.

Each paragraph (or table) is held to the results files it names (`bench/results/X.md`), or, naming
none, to those of the paragraph before it under the same heading; a paragraph with no named source
before it under its heading is held to all of bench/results/. A paragraph whose bold title says
"estimate" does arithmetic on measured figures and is not checked (it names its inputs' file).

Prints each figure without a source with its README line and exits 1; exits 0 when all are found.
"""
import bisect
import math
import pathlib
import re
import sys

NUMBER = re.compile(r"(?<![\w.^])(\d[\d,]*(?:\.\d+)?(?:e[-+]?\d+)?)(?![\w^⁰¹²³⁴⁵⁶⁷⁸⁹])")
NOT_FIGURES = [re.compile(r"`[^`]*`"),               # commands, file names, code
               re.compile(r"\(\d+\.\d+\)"),          # the chapter's equation numbers
               re.compile(r"[A-Z][a-z]+ (19|20)\d\d"),  # citations
               re.compile(r"\]\([^)]*\)")]           # link targets


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
    x = float(token)
    exponent = math.floor(math.log10(x))
    half = 0.5 * 10 ** (exponent - significant_digits(token) + 1) * (1 + 1e-9)
    i = bisect.bisect_left(values, x - half)
    return i < len(values) and values[i] <= x + half


def figures(block):
    for line in block.splitlines():
        if line.startswith("|") and "`bash" in line:  # the table of scripts
            continue
        text = line
        for pattern in NOT_FIGURES:
            text = pattern.sub(" ", text)
        for m in NUMBER.finditer(text):
            token = m.group(1).replace(",", "")
            if float(token) > 0 and (significant_digits(token) >= 2 or "e" in token):
                yield token, line


def blocks_with_sources(section, results):
    """(block, the results files it is held to) for each paragraph or table of the section."""
    sources = []
    section = re.sub(r"```.*?```", "", section, flags=re.S)  # examples, not figures
    for block in re.split(r"\n\s*\n", section):
        if block.startswith("#"):
            sources = []
            continue
        named = [results / n for n in re.findall(r"bench/results/([\w.]+)", block)]
        if named and not block.startswith("| figures"):
            sources = named
        if not re.match(r"\*\*[^*]*estimate", block):
            yield block, sources or sorted(p for p in results.rglob("*") if p.is_file())


def main():
    root = pathlib.Path(sys.argv[1])
    readme = (root / "README.md").read_text()
    section = readme[readme.index("## Choosing an integrator"):readme.index("## Known limits")]
    checked, missing = 0, 0
    for block, sources in blocks_with_sources(section, root / "bench" / "results"):
        values = result_numbers(sources)
        for token, line in figures(block):
            checked += 1
            if not has_source(token, values):
                missing += 1
                names = ", ".join(s.name for s in sources) if len(sources) < 4 else "bench/results/"
                print(f"README.md: {token} is in none of {names}: {line.strip()[:100]}")
    print(f"{checked - missing} of {checked} figures found in their sources")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
