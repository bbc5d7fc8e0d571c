"""platforms/pil_m4/platform.py - the emulated Cortex-M4F of
processor-in-the-loop: QEMU's netduinoplus2, an STM32F405, the e-puck2's
core (tools/make/images.py reads HYGIENE_COMPILERS; the make side is
platform.mk).

It runs the e-puck1's images as pil_avr generates them (the same
declarations over the same PIL run loop and HAL: platforms/pil_avr/run/ and
hal/, portable C over wire/pil/), built with the e-puck2's flags; only its
port (hal/pil_port_m4.c: a semihosting mailbox and the SysTick) and its bare-metal start
(startup/) are its own.  So it declares no images of its own.
"""

# tests/firmware/hygiene.sh builds this platform's HAL (its port) with it.
HYGIENE_COMPILERS = ['arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 -Os']
