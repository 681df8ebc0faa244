#!/bin/sh
# Build the macroscopic AFM's firmware with avr-gcc and Debian's Arduino core (arduino-core-avr),
# and the simavr harness with gcc -lsimavr. Usage:
#   hardware/macro_afm/build.sh [BUILD_DIR]       (default: build/macro_afm at the repo root)
# Outputs BUILD_DIR/macro_afm.elf, .hex, BUILD_DIR/size.txt (avr-size) and BUILD_DIR/harness.
# Environment: ARDUINO_AVR (core root), AVR_CC/AVR_CXX, CC; SKIP_HARNESS=1 builds only the firmware.
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
OUT=${1:-$ROOT/build/macro_afm}
ARDUINO_AVR=${ARDUINO_AVR:-/usr/share/arduino/hardware/arduino/avr}
AVR_CC=${AVR_CC:-avr-gcc}
AVR_CXX=${AVR_CXX:-avr-g++}
CC=${CC:-gcc}
CORE=$ARDUINO_AVR/cores/arduino
VARIANT=$ARDUINO_AVR/variants/mega
mkdir -p "$OUT/core" "$OUT/sketch"

# The flags of the Arduino IDE's platform.txt for the Mega 2560 (1.8.x), plus DECIMAL_DIG, which
# Debian's gcc-avr 5.4 does not define although the core's <float.h> users expect it.
DEFS="-mmcu=atmega2560 -DF_CPU=16000000L -DARDUINO=10807 -DARDUINO_AVR_MEGA2560 -DARDUINO_ARCH_AVR \
-DDECIMAL_DIG=9"
COMMON="-Os -g -Wall -ffunction-sections -fdata-sections -MMD -flto $DEFS -I$CORE -I$VARIANT"
CFLAGS="$COMMON -std=gnu11 -fno-fat-lto-objects"
CXXFLAGS="$COMMON -std=gnu++11 -fpermissive -fno-exceptions -fno-threadsafe-statics \
-Wno-error=narrowing"

# the core, as an archive (only what the sketch uses is linked)
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

# the sketch: the .ino is C++ once Arduino.h is included first (the IDE also adds prototypes;
# macro_afm.ino defines its functions before their use, so it needs none)
SK="$OUT/sketch"
{ echo '#include <Arduino.h>'; echo "#line 1 \"$HERE/firmware/macro_afm.ino\""; \
  cat "$HERE/firmware/macro_afm.ino"; } > "$SK/macro_afm.ino.cpp"
OBJS="$SK/macro_afm.ino.cpp.o"
$AVR_CXX $CXXFLAGS -Werror -I"$HERE/firmware" -c "$SK/macro_afm.ino.cpp" \
  -o "$SK/macro_afm.ino.cpp.o"
for src in "$HERE"/firmware/*.cpp; do
  obj="$SK/$(basename "$src").o"
  $AVR_CXX $CXXFLAGS -Werror -I"$HERE/firmware" -c "$src" -o "$obj"
  OBJS="$OBJS $obj"
done
$AVR_CC -Os -g -flto -fuse-linker-plugin -Wl,--gc-sections,--relax -mmcu=atmega2560 \
  -o "$OUT/macro_afm.elf" $OBJS "$OUT/core/core.a" -lm
avr-objcopy -O ihex -R .eeprom "$OUT/macro_afm.elf" "$OUT/macro_afm.hex"
avr-size -A "$OUT/macro_afm.elf" > "$OUT/size.txt"
avr-size --format=avr --mcu=atmega2560 "$OUT/macro_afm.elf" >> "$OUT/size.txt" 2>/dev/null || true
echo "firmware: $OUT/macro_afm.elf"

if [ "${SKIP_HARNESS:-0}" != 1 ]; then
  $CC -O2 -Wall -Wextra -std=gnu11 -I/usr/include/simavr -o "$OUT/harness" "$HERE/sim/harness.c" \
    -lsimavr -lutil -lm
  echo "harness: $OUT/harness"
fi
