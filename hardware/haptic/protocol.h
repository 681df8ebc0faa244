// protocol.h: the haptic device's serial protocol (device HAPTIC, protocol version 1).
//
// One place for every code of the protocol. afmsmiler/hardware/haptic/codec.py has the same
// names and values in its Command, ErrorCode, Event and Param enums, and a test parses this file
// and compares them (tests/test_hardware_haptic.py), so the two cannot drift.
// Only the contract's kinds of lines are here; the device's identity, baud rate and status
// flags are in config.h.
// The frame format (BODY*CC\n, CRC-8/SMBUS) is the module (h) contract's; see PROTOCOL.md.
#ifndef HAPTIC_PROTOCOL_H
#define HAPTIC_PROTOCOL_H

#define PROTOCOL_VERSION 1

// commands (host -> device); every one with SEQ != 0 gets one reply, FO is a SEQ 0 stream frame
#define CMD_IDENTIFY "ID"
#define CMD_SET "SP"
#define CMD_GET "GP"
#define CMD_ENABLE "EN"
#define CMD_DISABLE "DS"
#define CMD_ZERO "ZR"
#define CMD_STREAM "SS"
#define CMD_STATUS "ST"
#define CMD_ESTOP "ES"
#define CMD_FORCE "FO"
// frame codes the device sends: SEQ 0 stream frames and the two replies
#define CMD_POSITION "PO"
#define CMD_EVENT "EV"
#define CMD_OK "OK"
#define CMD_ERROR "ER"

// error numbers, shared by every device of module (h)
#define ERR_CHECKSUM 1
#define ERR_UNKNOWN_COMMAND 2
#define ERR_BAD_ARGUMENT 3
#define ERR_BUSY 4
#define ERR_NOT_HOMED 5
#define ERR_LIMIT 6
#define ERR_ESTOP 7
#define ERR_SENSOR 8
#define ERR_MALFORMED 9
#define ERR_STATE 10

// events: 0 EV <WORD>
#define EVT_BOOT "BOOT"
#define EVT_WATCHDOG "WATCHDOG"
#define EVT_ESTOP "ESTOP"
#define EVT_LIMIT "LIMIT"

// parameters: SP <PAR> <int> / GP <PAR>, units in the comments
#define PAR_MAX_FORCE "MF"       // uN, largest force magnitude the motor is asked for
#define PAR_FORCE_SCALE "FS"     // per mille, scale of the streamed FO force (1000 = 1:1)
#define PAR_SPRING "KS"          // mN/m, virtual spring about position 0 (the lever)
#define PAR_WALL_STIFFNESS "KW"  // mN/m, virtual wall (0: no wall)
#define PAR_WALL_POSITION "XW"   // um, the wall's face; it pushes back for x > XW
#define PAR_QGAIN "QG"           // 1/1000, Q-control gain g (relative to KS)
#define PAR_QPHASE "QP"          // millidegree, Q-control phase lag phi
#define PAR_QFREQ "QF"           // mHz, reference frequency f_ref of the phase shifter
#define PAR_WATCHDOG "WD"        // ms, force zeroed when no FO frame arrives for this long
#define PAR_VFILTER "VF"         // Hz, cut-off of the velocity estimate's low-pass
#define PAR_TRAVEL "XL"          // um, soft travel limit |x| <= XL
#define PAR_RESOLUTION "RE"      // nm per encoder count at the handle (read-only)
#define PAR_FORCE_CONSTANT "KT"  // uN per mA at the handle (read-only)
#define PAR_CURRENT_LIMIT "IL"   // mA, the amplifier's limit (read-only)

#endif
