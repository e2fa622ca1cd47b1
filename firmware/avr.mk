# Builds one board's firmware with Debian's avr-gcc and Arduino core: make -f firmware/avr.mk BOARD=nano|mega
# (run from the repository root). Users build with PlatformIO (platformio.ini); this is the same code.
ARDUINO_DIR ?= /usr/share/arduino/hardware/arduino/avr
BOARD ?= nano

ifeq ($(BOARD),nano)
MCU := atmega328p
VARIANT := standard
else ifeq ($(BOARD),mega)
MCU := atmega2560
VARIANT := mega
else
$(error BOARD must be nano or mega)
endif

OUT := build/avr
OBJ := $(OUT)/obj/$(BOARD)
CORE := $(ARDUINO_DIR)/cores/arduino
COMMON := firmware/common/protocol/src
PLANNER := firmware/common/planner/src
BOARD_SRC := firmware/$(BOARD)/src

# -MMD -MP: each object records its headers, so a changed header rebuilds what includes it.
CPPFLAGS := -MMD -MP -mmcu=$(MCU) -DF_CPU=16000000L -DARDUINO=10819 -DARDUINO_ARCH_AVR \
  -I$(CORE) -I$(ARDUINO_DIR)/variants/$(VARIANT) -I$(COMMON) -I$(PLANNER) -I$(BOARD_SRC) $(EXTRA_DEFS)
OPT := -Os -ffunction-sections -fdata-sections -flto
CFLAGS := $(OPT) -std=gnu11
CXXFLAGS := $(OPT) -std=gnu++11 -fno-exceptions -fno-threadsafe-statics -DDECIMAL_DIG=__DECIMAL_DIG__
WARN := -Wall -Wextra -Wno-missing-field-initializers
ASFLAGS := -x assembler-with-cpp

CORE_SRCS := $(wildcard $(CORE)/*.c $(CORE)/*.cpp $(CORE)/*.S)
APP_SRCS := $(wildcard $(COMMON)/*.cpp $(BOARD_SRC)/*.cpp $(BOARD_SRC)/hw/*.cpp)
ifeq ($(BOARD),mega)
APP_SRCS += $(wildcard $(PLANNER)/*.cpp)
endif
CORE_OBJS := $(patsubst $(CORE)/%,$(OBJ)/core/%.o,$(CORE_SRCS))
APP_OBJS := $(patsubst %,$(OBJ)/app/%.o,$(APP_SRCS))

all: $(OUT)/$(BOARD).elf $(OUT)/$(BOARD).hex

# The core goes in an archive, as the Arduino IDE and PlatformIO build it, so only the parts the
# firmware uses are linked (the Mega drives its host UARTs itself, without HardwareSerial0/2/3).
$(OBJ)/core.a: $(CORE_OBJS)
	rm -f $@
	avr-gcc-ar rcs $@ $^

$(OUT)/$(BOARD).elf: $(APP_OBJS) $(OBJ)/core.a
	avr-gcc -mmcu=$(MCU) $(OPT) -Wl,--gc-sections -o $@ $(APP_OBJS) $(OBJ)/core.a -lm

$(OUT)/$(BOARD).hex: $(OUT)/$(BOARD).elf
	avr-objcopy -O ihex -R .eeprom $< $@

$(OBJ)/core/%.c.o: $(CORE)/%.c
	@mkdir -p $(dir $@)
	avr-gcc $(CPPFLAGS) $(CFLAGS) -c $< -o $@
$(OBJ)/core/%.cpp.o: $(CORE)/%.cpp
	@mkdir -p $(dir $@)
	avr-g++ $(CPPFLAGS) $(CXXFLAGS) -c $< -o $@
$(OBJ)/core/%.S.o: $(CORE)/%.S
	@mkdir -p $(dir $@)
	avr-gcc $(CPPFLAGS) $(ASFLAGS) -c $< -o $@
$(OBJ)/app/%.cpp.o: %.cpp
	@mkdir -p $(dir $@)
	avr-g++ $(CPPFLAGS) $(CXXFLAGS) $(WARN) -Werror -c $< -o $@

-include $(CORE_OBJS:.o=.d) $(APP_OBJS:.o=.d)

.PHONY: all
