"""Which program a fake e-puck runs: the robot images declared in
platforms/epuck1/images.list, stand-in .hex files that carry an image's
identity, and reading that identity back from the program memory the
bootloader wrote.

A real image is built by XC16 (`make firmware`), which this machine may not
have.  A stand-in .hex is a valid dsPIC program (a reset GOTO to 0x200 and a
branch-to-self there) that the real flasher accepts and relocates as it
would any image, followed by an identity record: the text

    EPUCK-IMAGE:1:<image>:<declaration hash>

two bytes per instruction word (low and middle byte; the upper byte 0), as
the dsPIC's program-space visibility reads constants, at PC 0x300.  The
fake reads it back from the rows the bootloader wrote and runs that image's
declaration (its controller, period, telemetry, host link).  Today the
declaration runs as the host build in a simulated world (runtime.py); the
seam for running the flashed program itself on an emulated MCU is
runtime.runtime_for.
"""

from __future__ import annotations

import hashlib
import importlib.util
from dataclasses import dataclass
from functools import cache
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
IMAGES_LIST = "platforms/epuck1/images.list"
PLATFORM_DIR = "platforms/epuck1"
MAGIC = "EPUCK-IMAGE:1:"
ENTRY_PC = 0x200
IDENTITY_PC = 0x300
BRA_SELF = 0x37FFFF            # `bra .`: the stand-in program's main loop
ERASED = 0xFFFFFF


class ImageError(ValueError):
    """An image that is not declared, or a declaration list that is wrong
    (file and line)."""


@dataclass(frozen=True)
class ImageDecl:
    """One image of images.list: what a fake robot needs of it."""
    name: str
    controller: str
    period_ms: int
    telemetry: bool
    host_link: bool
    camera: bool
    sound: bool
    ir: str                     # the IR backend: randb (the turret's 16-bit messages) or libircom
    where: str                  # file:line of its declaration
    digest: str                 # hash of the declaration's text (16 hex digits)
    params: tuple               # ((field, C value), ...) as declared

    def describe(self) -> str:
        parts = [f"controller {self.controller}", f"{self.period_ms} ms"]
        parts += [k for k, on in (("telemetry", self.telemetry), ("host link", self.host_link),
                                  ("camera", self.camera), ("sound", self.sound)) if on]
        return f"{self.name} ({', '.join(parts)}; {self.where})"


def _images_module():
    """tools/make/images.py, the declarations' one reader."""
    path = ROOT / "tools" / "make" / "images.py"
    spec = importlib.util.spec_from_file_location("swarm_images_list", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@cache
def declarations(images_list: str = IMAGES_LIST, platform_dir: str = PLATFORM_DIR) -> dict[str, ImageDecl]:
    """Every image of the list, by name (ImageError: file and line)."""
    mod = _images_module()
    try:
        platform = mod.load_platform(platform_dir)
        images = mod.read_images(images_list, platform.IMAGE_KEYS)
    except mod.DeclarationError as e:
        raise ImageError(str(e)) from None
    out = {}
    for im in images:
        text = "\n".join([f"image {im.name}"] + [f"{k} {v}" for k, (v, _) in sorted(im.keys.items())]
                         + [f"param {f} {v}" for f, v, _ in im.params])
        out[im.name] = ImageDecl(
            name=im.name, controller=im.get("controller"), period_ms=int(im.get("period_ms") or 100),
            telemetry=im.get("telemetry") == "yes", host_link=im.get("host_link") == "yes",
            camera=im.get("camera") == "yes", sound=im.get("sound") == "yes",
            ir=im.get("ir"), where=im.where(),
            digest=hashlib.sha256(text.encode()).hexdigest()[:16],
            params=tuple((f, v) for f, v, _ in im.params))
    return out


def declaration(name: str) -> ImageDecl:
    decls = declarations()
    if name not in decls:
        raise ImageError(f"no image {name!r} in {IMAGES_LIST} (images: {', '.join(decls)})")
    return decls[name]


# ---------------------------------------------------------------- stand-in .hex

def _record(rtype: int, addr: int, data: bytes = b"") -> str:
    body = bytes([len(data), (addr >> 8) & 0xFF, addr & 0xFF, rtype]) + data
    return ":" + (body + bytes([(-sum(body)) & 0xFF])).hex().upper()


def _goto(target: int) -> tuple[int, int]:
    return 0x040000 | (target & 0xFFFE), (target >> 16) & 0x7F


def identity_text(decl: ImageDecl) -> str:
    return f"{MAGIC}{decl.name}:{decl.digest}"


def program_words(decl: ImageDecl) -> dict[int, int]:
    """{PC: 24-bit word} of the stand-in program of an image."""
    words = {}
    words[0], words[2] = _goto(ENTRY_PC)
    words[ENTRY_PC] = BRA_SELF
    text = identity_text(decl).encode("ascii") + b"\0"
    if len(text) % 2:
        text += b"\0"
    for k in range(0, len(text), 2):
        words[IDENTITY_PC + k] = text[k] | (text[k + 1] << 8)
    return words


def stand_in_hex(decl: ImageDecl) -> str:
    """The Intel HEX (INHX32, as XC16 writes it: 4 bytes per instruction at
    byte address 2 x PC, the 4th 0) of an image's stand-in program."""
    mem = {}
    for pc, w in program_words(decl).items():
        a = 2 * pc
        mem[a], mem[a + 1], mem[a + 2], mem[a + 3] = w & 0xFF, (w >> 8) & 0xFF, (w >> 16) & 0xFF, 0
    lines, addrs, i = [_record(4, 0, b"\x00\x00")], sorted(mem), 0
    while i < len(addrs):
        start, chunk = addrs[i], bytearray([mem[addrs[i]]])
        while i + len(chunk) < len(addrs) and addrs[i + len(chunk)] == start + len(chunk) and len(chunk) < 16:
            chunk.append(mem[start + len(chunk)])
        lines.append(_record(0, start & 0xFFFF, bytes(chunk)))
        i += len(chunk)
    lines.append(_record(1, 0))
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- program memory

def word(flash: dict[int, tuple[int, int, int]], pc: int) -> int:
    t = flash.get(pc)
    return ERASED if t is None else t[0] | (t[1] << 8) | (t[2] << 16)


def decode_goto(w0: int, w1: int) -> int | None:
    if (w0 >> 16) != 0x04 or (w1 & ~0x7F) != 0:
        return None
    return (w0 & 0xFFFE) | ((w1 & 0x7F) << 16)


@dataclass
class Program:
    """What a reset finds in program memory."""
    image: ImageDecl | None     # the declared image it identifies, or None
    robot_id: int               # the id word at 0x17F36 (0 when erased)
    entry: int | None           # where the relocated reset GOTO jumps
    note: str                   # why it does not run, or what differs ("" when all is well)


def read_program(flash: dict[int, tuple[int, int, int]]) -> Program:
    """The program the bootloader left: its relocated reset vector, the
    robot id the flasher wrote, and the image its identity record names."""
    if not any(p < 0x17F00 and t != (0xFF, 0xFF, 0xFF) for p, t in flash.items()):
        return Program(None, 0, None, "its program memory is empty: flash an image (epuck-flash)")
    id_word = word(flash, 0x17F36)
    robot_id = 0 if id_word == ERASED else id_word & 0xFFFF
    entry = decode_goto(word(flash, 0x17F38), word(flash, 0x17F3A))
    if decode_goto(word(flash, 0), word(flash, 2)) != 0x17F40:
        return Program(None, robot_id, entry, "the reset vector does not lead through the bootloader "
                                              "(PC 0 is not GOTO 0x17F40): not an image the flasher wrote")
    if entry is None:
        return Program(None, robot_id, None, "no program: the user reset GOTO at 0x17F38 is erased")
    text = _find_identity(flash)
    if text is None:
        return Program(None, robot_id, entry,
                       f"the program at 0x{entry:05X} carries no image identity: a fake e-puck runs the "
                       f"stand-in images of `swarm-fake-epuck hex` (the program itself runs on an emulated "
                       f"MCU only once one is wired in)")
    parts = text[len(MAGIC):].split(":")
    name = parts[0]
    decls = declarations()
    if name not in decls:
        return Program(None, robot_id, entry, f"the program is image {name!r}, which {IMAGES_LIST} does not "
                                              f"declare (any more)")
    decl = decls[name]
    note = ""
    if len(parts) > 1 and parts[1] != decl.digest:
        note = (f"image {name} was made from another declaration than {decl.where} now has: "
                f"running the current one")
    return Program(decl, robot_id, entry, note)


def _find_identity(flash) -> str | None:
    """The identity text, searched over every written word below the
    bootloader (PSV-style: two characters a word)."""
    first = ord(MAGIC[0]) | (ord(MAGIC[1]) << 8)
    for pc in sorted(p for p in flash if p < 0x17F00):
        if word(flash, pc) != first:
            continue
        chars = bytearray()
        for k in range(64):
            w = word(flash, pc + 2 * k)
            if w == ERASED or (w >> 16):
                break
            chars += bytes([w & 0xFF, (w >> 8) & 0xFF])
            if 0 in chars:
                break
        text = bytes(chars).split(b"\0", 1)[0].decode("ascii", errors="replace")
        if text.startswith(MAGIC):
            return text
    return None


__all__ = ["ImageDecl", "ImageError", "Program", "declaration", "declarations", "read_program", "stand_in_hex"]
