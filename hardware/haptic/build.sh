#!/bin/sh
# Build the haptic device's firmware for an Arduino Uno (ATmega328P) with avr-gcc and Debian's
# Arduino core (arduino-core-avr). Usage:
#   hardware/haptic/build.sh [BUILD_DIR]       (default: build/haptic at the repo root)
# Outputs BUILD_DIR/haptic.elf, .hex and BUILD_DIR/size.txt. Environment: ARDUINO_AVR (core root),
# AVR_CC/AVR_CXX, CC; SKIP_HARNESS=1 builds only the firmware (the simavr harness needs
# libsimavr-dev). Flash: avrdude -p m328p -c arduino -P /dev/ttyACM0 -U flash:w:haptic.hex
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
OUT=${1:-$ROOT/build/haptic}
ARDUINO_AVR=${ARDUINO_AVR:-/usr/share/arduino/hardware/arduino/avr}
AVR_CC=${AVR_CC:-avr-gcc}
AVR_CXX=${AVR_CXX:-avr-g++}
CORE=$ARDUINO_AVR/cores/arduino
VARIANT=$ARDUINO_AVR/variants/standard
mkdir -p "$OUT/core" "$OUT/sketch"

# the Arduino IDE's flags for the Uno (platform.txt 1.8.x), plus DECIMAL_DIG, which Debian's
# gcc-avr 5.4 does not define although the core's users expect it
DEFS="-mmcu=atmega328p -DF_CPU=16000000L -DARDUINO=10807 -DARDUINO_AVR_UNO -DARDUINO_ARCH_AVR \
-DDECIMAL_DIG=9"
COMMON="-Os -g -Wall -ffunction-sections -fdata-sections -flto $DEFS -I$CORE -I$VARIANT"
CFLAGS="$COMMON -std=gnu11 -fno-fat-lto-objects"
CXXFLAGS="$COMMON -std=gnu++11 -fpermissive -fno-exceptions -fno-threadsafe-statics"

rm -f "$OUT/core/core.a"
for src in "$CORE"/*.c "$CORE"/*.cpp "$CORE"/*.S; do
  obj="$OUT/core/$(basename "$src").o"
  case $src in
    *.c) $AVR_CC $CFLAGS -c "$src" -o "$obj" ;;
    *.cpp) $AVR_CXX $CXXFLAGS -c "$src" -o "$obj" ;;
    *.S) $AVR_CC -x assembler-with-cpp $COMMON -c "$src" -o "$obj" ;;
  esac
  avr-gcc-ar rcs "$OUT/core/core.a" "$obj"
done

# the sketch is C++ once Arduino.h comes first (haptic.ino defines functions before their use)
SK="$OUT/sketch"
{ echo '#include <Arduino.h>'; echo "#line 1 \"$HERE/haptic.ino\""; cat "$HERE/haptic.ino"; } \
  > "$SK/haptic.ino.cpp"
$AVR_CXX $CXXFLAGS -Werror -I"$HERE" -c "$SK/haptic.ino.cpp" -o "$SK/haptic.ino.cpp.o"
$AVR_CC -Os -g -flto -fuse-linker-plugin -Wl,--gc-sections -mmcu=atmega328p \
  -o "$OUT/haptic.elf" "$SK/haptic.ino.cpp.o" "$OUT/core/core.a" -lm
avr-objcopy -O ihex -R .eeprom "$OUT/haptic.elf" "$OUT/haptic.hex"
avr-size -A "$OUT/haptic.elf" > "$OUT/size.txt"
echo "firmware: $OUT/haptic.elf"

if [ "${SKIP_HARNESS:-0}" != 1 ]; then
  ${CC:-gcc} -O2 -Wall -Wextra -std=gnu11 -I/usr/include/simavr -o "$OUT/harness" \
    "$HERE/sim/harness.c" -lsimavr -lutil -lm
  echo "harness: $OUT/harness"
fi
