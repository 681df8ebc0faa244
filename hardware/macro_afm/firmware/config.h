// config.h: pins, mechanics and limits of the macroscopic AFM (see ../WIRING.md and ../BUILD.md).
// The sim harness (../sim/harness.c) uses the same pins; change both together.
#ifndef MACRO_AFM_CONFIG_H
#define MACRO_AFM_CONFIG_H

#define FIRMWARE_VERSION "0.1.0"
#define DEVICE_NAME "MACROAFM"
#define BAUD_RATE 115200L

// -- pins (Arduino Mega 2560 numbering; port/bit in brackets) ------------------------------------
#define PIN_X_STEP 22   // PA0
#define PIN_X_DIR 23    // PA1
#define PIN_Y_STEP 24   // PA2
#define PIN_Y_DIR 25    // PA3
#define PIN_Z_STEP 26   // PA4
#define PIN_Z_DIR 27    // PA5
#define PIN_ENABLE 28   // PA6, all drivers' ENABLE (active low)
#define PIN_HX_DOUT 30  // PC7, HX711 DOUT
#define PIN_HX_SCK 31   // PC6, HX711 PD_SCK
#define PIN_X_MIN 32    // PC5, limit switches: closed = LOW (INPUT_PULLUP)
#define PIN_X_MAX 33    // PC4
#define PIN_Y_MIN 34    // PC3
#define PIN_Y_MAX 35    // PC2
#define PIN_Z_MIN 36    // PC1, bottom of the z travel (tip at the bed)
#define PIN_Z_MAX 37    // PC0, top of the z travel (home)
#define PIN_BTN_START 42   // PL7, push button: start preset PR (closed = LOW)
#define PIN_BTN_SELECT 43  // PL6, push button: next preset
#define PIN_ESTOP 10    // PB4 = PCINT4; NC mushroom switch to GND: open (HIGH) = emergency stop
#define PIN_LED 13      // PB7, on while scanning, blinks in FAULT

// -- mechanics (Ender 3: GT2 belt on 20-tooth pulleys for x and y, T8 8 mm lead screw for z,
//    1.8 degree motors at 1/16 micro-steps) ------------------------------------------------------
#define XY_STEP_NM 12500L   // 80 micro-steps per mm
#define Z_STEP_NM 2500L     // 400 micro-steps per mm (the paper's 0.0025 mm z micro-step)
#define X_TRAVEL_STEPS 18800L  // 235 mm
#define Y_TRAVEL_STEPS 18800L
#define Z_TRAVEL_STEPS 100000L  // 250 mm
#define HOME_SPEED 1600L       // steps/s towards a switch (20 mm/s in x, y; 4 mm/s in z)
#define HOME_BACKOFF 80L       // steps moved off a switch after it opens: the axis' zero

// -- scan limits ----------------------------------------------------------------------------------
#define MAX_NX 128          // pixels per line (two lines are kept for GETLINE: 2 KB of RAM)
#define MAX_NY 1024
#define MIN_PITCH_UM 25     // DX must be a multiple of 25 um (two x/y micro-steps)
#define MAX_PITCH_UM 10000
#define MAX_LIFT 40000L
#define MIN_SPEED 10L
#define MAX_SPEED 8000L     // the loop-driven step generator keeps up to about this rate
#define MIN_ACCEL 10L
#define MAX_ACCEL 1000000L
#define N_PRESETS 4

// -- regulation -----------------------------------------------------------------------------------
#define FREE_SAMPLES 8        // gauge readings averaged for the free (out of contact) level
#define CONTACT_COUNTS 300L   // |reading - free| above which the tip touches (over the noise)
#define CAL_STEPS 20L         // z micro-steps pressed in at the first contact to learn counts/step
#define MAX_REG_ITER 8        // regulation iterations per pixel before it is recorded anyway
#define SETTLE_MS 0           // wait after each move before the gauge is trusted (see BUILD.md)
#define SENSOR_TIMEOUT_MS 500 // no HX711 reading for this long: ERR_SENSOR
#define APPROACH_SENSOR_MS 150  // ... or this long while descending blind (HX711 at 10/s: 100 ms)

#endif
