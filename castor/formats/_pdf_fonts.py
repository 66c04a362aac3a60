"""The PDF's fonts: Helvetica, one of PDF's standard fonts, for every text its
encoding (WinAnsi: Latin-1 with Œ, –, €, …) holds, so that such a PDF keeps
its bytes; for a text with other characters (ĉ, ł, Ω), an embedded TrueType
font that has them, found on this machine (nothing is downloaded); where
none has them, a warning names them. Imported by castor.formats.pdf and, for
the warning, by castor.formats.kinds; reportlab only when a PDF is made."""

from __future__ import annotations

# TrueType fonts for text that Helvetica's encoding (WinAnsi: Latin-1, Œ, –, €
# ...) lacks, the first that has every character of the text embedded (a
# subset): reportlab's own Vera, then DejaVu Sans (Vera's glyphs, extended to
# most scripts) where a Linux system keeps it (Debian's fonts-dejavu-core ...)
SYSTEM_FONTS = ("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",  # Debian, Ubuntu
                "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf",  # Fedora
                "/usr/share/fonts/TTF/DejaVuSans.ttf",  # Arch
                "/usr/share/fonts/truetype/DejaVuSans.ttf",  # openSUSE
                "/usr/share/fonts/dejavu/DejaVuSans.ttf")
_FONTS: dict = {}  # font file -> (its name for reportlab, the characters it has), once read


def font_files() -> list[str]:
    """The TrueType fonts a PDF may embed, in the order they are tried."""
    import os

    import reportlab

    own = os.path.join(os.path.dirname(reportlab.__file__), "fonts", "Vera.ttf")
    return [path for path in (own, *SYSTEM_FONTS) if os.path.isfile(path)]


def _helvetica_has(text: str) -> bool:
    import reportlab.pdfbase.pdfmetrics  # noqa: F401  (registers the codec "winansi")

    try:
        text.encode("winansi")
        return True
    except UnicodeEncodeError:
        return False


def _font_file(path: str):
    """A TrueType font registered with reportlab: its name and characters."""
    if path not in _FONTS:
        from reportlab.pdfbase import pdfmetrics
        from reportlab.pdfbase.ttfonts import TTFont, TTFError

        name = "Castor-" + path.rsplit("/", 1)[-1].removesuffix(".ttf")
        try:
            font = TTFont(name, path)
            pdfmetrics.registerFont(font)
            _FONTS[path] = (name, set(font.face.charToGlyph))
        except (TTFError, OSError):
            _FONTS[path] = (None, set())
    return _FONTS[path]


def _chosen(text: str) -> tuple[str, set]:
    """The font for ``text`` and the characters it lacks: Helvetica when its
    encoding has them all, else the first of font_files that has them all,
    else the one that lacks the fewest."""
    if _helvetica_has(text):
        return "Helvetica", set()
    best = ("Helvetica", {c for c in text if not _helvetica_has(c)})
    for path in font_files():
        name, has = _font_file(path)
        lacks = {c for c in text if ord(c) not in has}
        if name and len(lacks) < len(best[1]):
            best = (name, lacks)
        if not best[1]:
            break
    return best


def font_for(text: str) -> str:
    """The font a text is set in (_chosen): Helvetica, PDF's standard font,
    whenever its encoding will do, so that such a PDF keeps its bytes."""
    return _chosen(text)[0]


def unprintable(product) -> tuple[str, list[str]]:
    """The characters of a sheet's or a set's texts that their font lacks
    (printed as a box), in order, and the texts that hold them, in order."""
    from castor.drawings.paper import Text

    sheets = product.sheets if hasattr(product, "sheets") else [product]
    texts = {item.text for sheet in sheets for group in [*sheet.layers, *sheet.groups]
             for item in group.items if isinstance(item, Text)}
    if hasattr(product, "sheets"):  # the index's
        texts |= {str(v) for v in product.project.values()}
        texts |= {entry.title for entry in product.entries}
    lacking = {text: _chosen(text)[1] for text in texts}
    return ("".join(sorted(set().union(*lacking.values()))),
            sorted(text for text, lacks in lacking.items() if lacks))


def missing_glyphs_warning(product, warn) -> None:
    """A warning naming the characters the PDF of a sheet or set prints as a box,
    and the texts they are in (a title from the command line, a room's name: the
    warning's place is the frame's '>' whatever the text's origin)."""
    missing, texts = unprintable(product)
    if missing:
        shown = ", ".join(repr(t) for t in texts[:3]) + (", …" if len(texts) > 3 else "")
        warn(f"no font the PDF can have has {', '.join(repr(c) for c in missing)} (in "
             f"{shown}): printed as a box (castor embeds reportlab's Vera, or DejaVu Sans where "
             "the system has it: Debian's fonts-dejavu-core)")
