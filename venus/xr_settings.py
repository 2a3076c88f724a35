"""This device's settings in Venus OS's localsettings
(com.victronenergy.settings): the device instance and the custom name.

  AddSetting(group, name, default, type, min, max) -> i   on /Settings
      (interface com.victronenergy.Settings; name relative to /Settings/;
      an existing setting keeps its stored value)
  GetValue / SetValue / PropertiesChanged                  on /Settings/<name>
      (com.victronenergy.BusItem)

The instance is /Settings/Devices/<unique>/ClassAndVrmInstance, default
"alternator:<n>": the GX's device list lets the owner change the number, and
the driver follows (PropertiesChanged). Without localsettings (not a GX, or
it never came up) the default instance is used and the log says so.
"""
import logging
import time

import dbus

SETTINGS = "com.victronenergy.settings"
SETTINGS_IFACE = "com.victronenergy.Settings"
BUSITEM = "com.victronenergy.BusItem"

log = logging.getLogger("dbus-xregulator")


def parse_instance(text, default):
    """'alternator:3' -> 3; anything else (another class, no number) -> default."""
    cls, _, num = str(text).partition(":")
    if cls != "alternator" or not num.isdigit():
        return default
    return int(num)


class DeviceSettings:
    def __init__(self, bus, unique, default_instance, wait_s=30.0):
        self.bus = bus
        self.default = default_instance
        self.instance = default_instance
        self.custom_name = ""
        self.on_instance = None
        self.base = f"/Settings/Devices/{unique}/"
        self.available = self._wait(wait_s)
        if not self.available:
            log.warning("no localsettings (%s) after %.0f s: device instance %d, custom name not kept",
                        SETTINGS, wait_s, default_instance)
            return
        try:
            self._add("ClassAndVrmInstance", f"alternator:{default_instance}")
            self._add("CustomName", "")
            self.instance = parse_instance(self._get("ClassAndVrmInstance"), default_instance)
            self.custom_name = str(self._get("CustomName") or "")
            bus.add_signal_receiver(self._instance_changed, signal_name="PropertiesChanged", dbus_interface=BUSITEM,
                                    bus_name=SETTINGS, path=self.base + "ClassAndVrmInstance")
        except dbus.DBusException as e:
            self.available = False
            log.warning("localsettings refused our settings (%s): device instance %d", e, default_instance)

    def _wait(self, wait_s):
        end = time.monotonic() + wait_s
        while True:
            try:
                if self.bus.name_has_owner(SETTINGS):
                    return True
            except dbus.DBusException:
                pass
            if time.monotonic() >= end:
                return False
            time.sleep(0.2)

    def _add(self, name, default):
        obj = self.bus.get_object(SETTINGS, "/Settings")
        rc = obj.AddSetting("", self.base[len("/Settings/"):] + name, dbus.String(default), "s", dbus.Int32(0),
                            dbus.Int32(0), dbus_interface=SETTINGS_IFACE)
        if rc != 0:
            raise dbus.DBusException(f"AddSetting {name} answered {rc}")

    def _get(self, name):
        return self.bus.get_object(SETTINGS, self.base + name).GetValue(dbus_interface=BUSITEM)

    def _instance_changed(self, changes):
        n = parse_instance(changes.get("Value", ""), self.default)
        if n != self.instance:
            log.info("device instance changed in the settings: %d -> %d", self.instance, n)
            self.instance = n
            if self.on_instance:
                self.on_instance(n)

    def set_custom_name(self, name):
        self.custom_name = name
        if not self.available:
            return
        try:
            self.bus.get_object(SETTINGS, self.base + "CustomName").SetValue(
                dbus.String(name), dbus_interface=BUSITEM)
        except dbus.DBusException as e:
            log.warning("could not keep the custom name in localsettings: %s", e)
