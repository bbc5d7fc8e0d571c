"""platforms/pil_avr/platform.py - the emulated ATmega2560 of
processor-in-the-loop (tools/make/images.py reads IMAGES, IMAGE_KEYS and
HYGIENE_COMPILERS; the make side is platform.mk).

Its images are the e-puck1's: the same declarations (IMAGES), with the
e-puck1's keys (read from its platform.py, so they are written once), built
over this platform's run loop (run/image_main.h) and HAL (hal/, over the PIL
protocol of wire/pil/) with avr-gcc for the ATmega2560: 16-bit int and
pointers, 32-bit double, 8 KB of RAM, the data model of XC16 on the e-puck1's
dsPIC30F6014A.  simavr runs them (emu/, a program of its own: GPL-3).
"""
import importlib.util
import os

HERE = 'platforms/pil_avr'

# The e-puck1's images, emulated.
IMAGES = 'platforms/epuck1/images.list'


def _epuck1():
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'epuck1', 'platform.py')
    spec = importlib.util.spec_from_file_location('platform_epuck1_for_pil_avr', path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


# The declarations' keys are the e-puck1's (run/image_main.h says what each
# means here).
IMAGE_KEYS = _epuck1().IMAGE_KEYS

# tests/firmware/hygiene.sh builds the HAL, run loop and images with these;
# the first one's objects are checked for writable statics and allocators.
# avr-gcc only: the port (hal/pil_port_avr.c) writes the ATmega2560's I/O
# registers by address, which is this chip's code (the rest builds on the
# host too: the comparison's host build, platform.mk).
HYGIENE_COMPILERS = ['avr-gcc -mmcu=atmega2560 -Os']
