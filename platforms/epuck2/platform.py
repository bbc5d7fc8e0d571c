"""platforms/epuck2/platform.py - the e-puck2 (STM32F407, Cortex-M4F, over
GCtronic's e-puck2 main-processor library and ChibiOS): what its images
declare (tools/make/images.py reads IMAGES, IMAGE_KEYS and
HYGIENE_COMPILERS) and how the portable gates build and measure them
(tests/firmware/image_gates.py reads GATES).  The make side (its host
tests, the real build against a user's checkout of the library) is
platform.mk; the robot's page is docs/hardware/epuck2.md.

Its images are the e-puck1's declarations (IMAGES), with the e-puck1's keys
(read from its platform.py, so they are written once): every shipped
controller runs on both robots unchanged.  On the e-puck2 `ir randb` is the
range-and-bearing turret over the I2C bus, `ir libircom` the library's port
of libIrcom (src/ircom/).

The gates link every image, with this HAL, against stubs of the library
and of the ChibiOS glue (tests/stubs/) with the e-puck2's compiler and
flags: arm-none-eabi-gcc, Cortex-M4F, hard float (the library's Makefile:
MCU cortex-m4, USE_FPU hard, thumb).
"""
import importlib.util
import os

HERE = 'platforms/epuck2'
STUBS = HERE + '/tests/stubs'

# The e-puck1's images, on the e-puck2.
IMAGES = 'platforms/epuck1/images.list'


def _epuck1():
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'epuck1', 'platform.py')
    spec = importlib.util.spec_from_file_location('platform_epuck1_for_epuck2', path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


# The declarations' keys are the e-puck1's (run/image_main.h says what each
# means here).
IMAGE_KEYS = _epuck1().IMAGE_KEYS

# The e-puck2's core and float ABI, as the library's Makefile builds it.
ARCH = '-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16'

# tests/firmware/hygiene.sh builds the HAL, run loop and images with these
# (warning-free, each layer on its own include path); the first one's
# objects are checked for writable statics and allocators.
HYGIENE_COMPILERS = ['cc -fno-pie -O2', 'arm-none-eabi-gcc ' + ARCH + ' -Os']

GATES = {
    'include': [HERE + '/hal', HERE + '/run', STUBS],
    'sources': [HERE + '/hal/hal_epuck2.c', HERE + '/hal/host_link.c', HERE + '/hal/tone_coeffs_16k.c'],
    'stubs': [STUBS + '/epuck2_lib_stubs.c', STUBS + '/epuck2_os_stubs.c'],
    'when': {
        ('ir', 'randb'): ([HERE + '/hal/ircom_randb.c'], []),
        ('ir', 'libircom'): ([HERE + '/hal/ircom_libircom.c'], [STUBS + '/ircom_stubs.c']),
        ('telemetry', 'yes'): ([HERE + '/run/image_telemetry.c'], []),
    },
    'targets': {
        'arm': {
            'cc': 'arm-none-eabi-gcc',
            'cflags': ARCH,
            'ldflags': ARCH + ' --specs=nano.specs --specs=nosys.specs -Wl,--gc-sections',
            'objdump': 'arm-none-eabi-objdump',
            'ret_bytes': 0,
            'what': 'arm-none-eabi-gcc Cortex-M4F, hard float (the e-puck2\'s STM32F407)',
            'label': 'STM32F407',
        },
    },
    # The budgets, on the STM32F407 (1 MB flash; 128 KB SRAM + 64 KB CCM,
    # of which ChibiOS, the library's threads and buffers take their part:
    # the DCMI buffer alone is 38,400 B).  Our static RAM <= 8 KB; the
    # stack estimate <= 3 KB of the 4 KB main-thread stack the real build
    # gives (chibios/Makefile, USE_PROCESS_STACKSIZE = 0x1000: the rest for
    # the exception frames the Cortex-M4F stacks on it, 104 B with the FPU's
    # registers, and ChibiOS's context switches); our flash <= 128 KB.
    'ram_gate': ('arm', 8192),
    'stack_gate': 3072,
    'flash_gate': 131072,
    # No callback of ours runs in an interrupt: the clock is ChibiOS's.
    'interrupts': [],
    'frames': 'camera_frames',
    'column': ('ir', 'IR backend'),
    'notes': [
        'Bytes, measured with arm-none-eabi-gcc -Os for the Cortex-M4F with hard float (the '
        'e-puck2\'s STM32F407), against stubs of the e-puck2 library and of ChibiOS.',
        'Static RAM: .data + .bss of our objects after --gc-sections, without the camera frame '
        '(one 40 x 20 RGB565 frame, 1,600 B: the capture is in the library\'s DCMI buffer), the '
        'library and the C library.  Stack estimate: the worst call chain from main (frames from '
        '-fstack-usage; LR is saved inside each frame).  Flash: our .text + .rodata + .data '
        'initialisers; "image flash" adds the stubs and the C library, not ChibiOS nor the library.',
    ],
}
