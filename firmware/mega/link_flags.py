# `pio run`'s link line for the Mega. Under -flto the link runs the compiler again, and
# --gc-sections drops a dead vtable only when -ffunction-sections -fdata-sections are on that line
# too; platform-atmelavr puts them on the compile lines only, and build_flags never reach the
# link (PlatformIO's docs, "Extra linker flags without -Wl, prefix"). Three vtables no code uses
# (StopSource, CellSource, SegmentSink) then stay in RAM: 37 B, measured by hand (card_ram.txt).
Import("env")  # noqa: F821 (PlatformIO's SCons gives it)

env.Append(LINKFLAGS=["-ffunction-sections", "-fdata-sections"])  # noqa: F821
