"""platforms/epuck1/platform.py - what the e-puck1's images may declare
(tools/make/images.py reads IMAGE_KEYS) and how the portable gates build and
measure them (tests/firmware/image_gates.py reads GATES).  The make side of
the platform (XC16, its host tests, flashing) is platform.mk.

The gates link every image, with this HAL, against stubs of GCtronic's
library (tests/stubs/) for two targets:

  avr  avr-gcc -mmcu=atmega2560: 16-bit int and pointers, 32-bit double, the
       data model of XC16 on the dsPIC30F6014A, and 8 KB of RAM like it;
  arm  arm-none-eabi-gcc for a Cortex-M4F (the e-puck2's STM32F407 class).
"""

HERE = 'platforms/epuck1'

# The image keys of this platform (images.list has their meaning).  Their
# defaults are the run loop's (run/image_main.h) and the HAL's.
IMAGE_KEYS = {
    'ir': {'choices': ('randb', 'libircom'), 'required': True},
    'camera': {'choices': ('yes', 'no')},
    'period_ms': {'type': 'int'},
    'sound': {'choices': ('yes', 'no')},
    'ircom_tx_per_period': {'type': 'int'},
    'host_link': {'choices': ('yes', 'no')},
}

STUBS = HERE + '/tests/stubs'

# The compilers tests/firmware/hygiene.sh builds this platform's HAL, run
# loop and images with (warning-free, each layer on its own include path);
# the first one's objects are checked for writable statics and allocators.
# The e-puck1's: the host's, and avr-gcc for the dsPIC's 16-bit int.
HYGIENE_COMPILERS = ['cc -fno-pie -O2', 'avr-gcc -mmcu=atmega128 -Os']

GATES = {
    # Include folders of the platform (besides hal/, wire/, firmware/ and
    # lcm-gen's), for its sources and its images' mains.
    'include': [HERE + '/hal', HERE + '/run', STUBS],
    # Linked into every image (--gc-sections keeps what it uses).
    'sources': [HERE + '/hal/hal_epuck.c', HERE + '/hal/host_link.c'],
    # The library's stand-ins: linked, but not ours (not in "our" RAM and flash).
    'stubs': [STUBS + '/epuck_lib_stubs.c'],
    # What an image's keys add: (our sources, stubs).
    'when': {
        ('ir', 'randb'): ([HERE + '/hal/ircom_randb.c'],
                          [STUBS + '/adscan_stubs.c', STUBS + '/randb_stubs.c']),
        ('ir', 'libircom'): ([HERE + '/hal/ircom_libircom.c'], [STUBS + '/ircom_stubs.c']),
        ('telemetry', 'yes'): ([HERE + '/run/image_telemetry.c'], []),
    },
    'targets': {
        'avr': {
            'cc': 'avr-gcc',
            'cflags': '-mmcu=atmega2560',
            'ldflags': '-mmcu=atmega2560 -Wl,--gc-sections',
            'objdump': 'avr-objdump',
            'ret_bytes': 3,
            'what': 'avr-gcc atmega2560 (16-bit int, XC16 data model, 8 KB RAM)',
            'label': 'atmega2560',
        },
        'arm': {
            'cc': 'arm-none-eabi-gcc',
            'cflags': '-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16',
            'ldflags': ('-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 '
                        '--specs=nano.specs --specs=nosys.specs -Wl,--gc-sections'),
            'objdump': 'arm-none-eabi-objdump',
            'ret_bytes': 0,
            'what': 'arm-none-eabi-gcc Cortex-M4F (e-puck2 class)',
            'label': 'Cortex-M4F',
        },
    },
    # The static RAM gate: our .data + .bss on this target (the dsPIC's 8 KB
    # must also hold the library's buffers, the camera frames and the stacks).
    'ram_gate': ('avr', 2048),
    # The timer agenda callback, which interrupts main anywhere: its chain is
    # added to main's.
    'interrupts': ['app_tick'],
    # Static buffers reported in their own column, not in the static RAM.
    'frames': 'camera_frames',
    # The key the table shows beside the image, and its heading.
    'column': ('ir', 'IR backend'),
    # What the table's figures are (footprint.md).
    'notes': [
        'Bytes, measured with avr-gcc -Os for the atmega2560 (16-bit int and pointers, 32-bit '
        'double: the data model of XC16 on the dsPIC30F6014A) unless marked Cortex-M4F.',
        'Static RAM: .data + .bss of our objects after --gc-sections, without the camera frames, '
        'the library (stubs) and the C library; const data is counted as flash (XC16 keeps it in '
        'program memory). Stack estimate: the worst call chain from main plus that of the timer '
        'agenda callback (frames from -fstack-usage, return addresses of 3 bytes).  Flash: our '
        '.text + .rodata + .data initialisers; "image flash" adds the stubs, libgcc and libc '
        '(8-bit AVR code: the dsPIC\'s is smaller).',
    ],
    # The documentation's footprint table (docs/hardware/footprint.md,
    # readme_footprint.py) is this platform's.
    'readme': True,
}
