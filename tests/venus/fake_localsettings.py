#!/usr/bin/env python3
"""A stand-in for Venus OS's localsettings (com.victronenergy.settings) on
the bus the environment gives (DBUS_SYSTEM_BUS_ADDRESS), for the GX driver's
tests. It answers the calls the driver makes, the way localsettings does:

  /Settings  com.victronenergy.Settings
     AddSetting(s group, s name, v default, s type, v min, v max) -> i
        creates /Settings/<group/>name with the default, type i, f or s
        (0 = done, -1 = a bad type); a setting that exists keeps its value
        (and answers 0), as localsettings keeps what the owner chose
  /Settings/<name>  com.victronenergy.BusItem
     GetValue() -> v, GetText() -> s, SetValue(v) -> i (0; the type is
     kept: an int setting takes an int), signal PropertiesChanged(a{sv})

Not covered: AddSettings (the batch call of newer Venus OS),
AddSilentSetting, RemoveSettings, min/max clamping, the XML file
localsettings keeps (values live as long as this process), and the
ClassAndVrmInstance de-duplication of newer localsettings.
"""
import signal
import sys

import dbus
import dbus.service
from dbus.mainloop.glib import DBusGMainLoop
from gi.repository import GLib

BUSITEM = "com.victronenergy.BusItem"


class Setting(dbus.service.Object):
    def __init__(self, bus, path, value):
        super().__init__(bus, path)
        self.value = value

    @dbus.service.method(BUSITEM, out_signature="v")
    def GetValue(self):
        return self.value

    @dbus.service.method(BUSITEM, out_signature="s")
    def GetText(self):
        return str(self.value)

    @dbus.service.method(BUSITEM, in_signature="v", out_signature="i")
    def SetValue(self, value):
        try:
            value = type(self.value)(value)
        except (TypeError, ValueError):
            return -1
        if value != self.value:
            self.value = value
            self.PropertiesChanged({"Value": value, "Text": str(value)})
        return 0

    @dbus.service.signal(BUSITEM, signature="a{sv}")
    def PropertiesChanged(self, changes):
        pass


class Settings(dbus.service.Object):
    TYPES = {"i": dbus.Int32, "f": dbus.Double, "s": dbus.String}

    def __init__(self, bus):
        super().__init__(bus, "/Settings")
        self.bus = bus
        self.items = {}

    @dbus.service.method("com.victronenergy.Settings", in_signature="ssvsvv", out_signature="i")
    def AddSetting(self, group, name, default, kind, lo, hi):
        if kind not in self.TYPES:
            return -1
        path = "/Settings/" + "/".join(p for p in (group.strip("/"), name.strip("/")) if p)
        if path not in self.items:
            self.items[path] = Setting(self.bus, path, self.TYPES[kind](default))
            print(f"localsettings: added {path} = {default}", flush=True)
        return 0


def main():
    DBusGMainLoop(set_as_default=True)
    bus = dbus.SystemBus()
    settings = Settings(bus)
    settings.name = dbus.service.BusName("com.victronenergy.settings", bus, do_not_queue=True)
    print("localsettings: ready", flush=True)
    loop = GLib.MainLoop()
    for sig in (signal.SIGTERM, signal.SIGINT):
        GLib.unix_signal_add(GLib.PRIORITY_HIGH, sig, loop.quit)
    loop.run()
    return 0


if __name__ == "__main__":
    sys.exit(main())
