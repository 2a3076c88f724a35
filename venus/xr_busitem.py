"""The com.victronenergy.BusItem export of one D-Bus service, as Venus OS's
own services behave (velib_python's vedbus.py, written anew here):

  one object per path     GetValue() -> v, SetValue(v) -> i (0 accepted,
                          non-zero refused), GetText() -> s,
                          GetDescription(s, i) -> s, signal
                          PropertiesChanged(a{sv}) with Value and Text
  the root object "/"     GetItems() -> a{sa{sv}} (path -> Value, Text),
                          GetValue()/GetText() -> every path under it,
                          signal ItemsChanged(a{sa{sv}}) for a batch
  inner nodes (/Dc/0)     GetValue()/GetText() of the paths under them

An invalid value is an empty int32 array (`ai`, []) and its text "---".
Everything here runs on the GLib main loop's thread (dbus-python is not
thread-safe): values change through ServiceTree.set() and reach the bus,
batched, at flush().
"""
import dbus
import dbus.service

IFACE = "com.victronenergy.BusItem"


def invalid():
    return dbus.Array([], signature=dbus.Signature("i"), variant_level=1)


def wrap(value):
    """A Python value as the D-Bus variant a Venus OS service would send."""
    if value is None:
        return invalid()
    if isinstance(value, bool):
        return dbus.Int32(int(value), variant_level=1)
    if isinstance(value, int):
        if -0x80000000 <= value <= 0x7FFFFFFF:
            return dbus.Int32(value, variant_level=1)
        return dbus.Int64(value, variant_level=1)
    if isinstance(value, float):
        return dbus.Double(value, variant_level=1)
    return dbus.String(str(value), variant_level=1)


def unwrap(value):
    """A D-Bus value from a writer as plain Python; an empty array = None."""
    if isinstance(value, dbus.Array):
        return None if len(value) == 0 else [unwrap(v) for v in value]
    if isinstance(value, dbus.Boolean):
        return bool(value)
    if isinstance(value, (dbus.Byte, dbus.Int16, dbus.Int32, dbus.Int64, dbus.UInt16, dbus.UInt32, dbus.UInt64)):
        return int(value)
    if isinstance(value, dbus.Double):
        return float(value)
    if isinstance(value, (dbus.String, dbus.ObjectPath, dbus.Signature)):
        return str(value)
    return value


class Item:
    """One path's value, text format and write rule."""

    def __init__(self, path, value=None, fmt=None, on_write=None, description=""):
        self.path = path
        self.value = value
        self.fmt = fmt  # callable value -> text; None: str(value)
        self.on_write = on_write  # callable (path, value) -> bool; None: read-only
        self.description = description

    def text(self):
        if self.value is None:
            return "---"
        return self.fmt(self.value) if self.fmt else str(self.value)


class _ItemObject(dbus.service.Object):
    def __init__(self, tree, bus, item):
        super().__init__(bus, item.path)
        self._tree = tree
        self._item = item

    @dbus.service.method(IFACE, out_signature="v")
    def GetValue(self):
        return wrap(self._item.value)

    @dbus.service.method(IFACE, out_signature="s")
    def GetText(self):
        return self._item.text()

    @dbus.service.method(IFACE, in_signature="si", out_signature="s")
    def GetDescription(self, language, length):
        return self._item.description or self._item.path

    @dbus.service.method(IFACE, in_signature="v", out_signature="i")
    def SetValue(self, value):
        return self._tree.write(self._item.path, unwrap(value))

    @dbus.service.signal(IFACE, signature="a{sv}")
    def PropertiesChanged(self, changes):
        pass


class _NodeObject(dbus.service.Object):
    """The root ("/") or an inner node: the values of every path under it,
    keyed relative to it (Dc/0/Voltage from "/"), as velib's tree export."""

    def __init__(self, tree, bus, path):
        super().__init__(bus, path)
        self._tree = tree
        self._prefix = "/" if path == "/" else path + "/"

    def _under(self):
        n = len(self._prefix)
        return [(p[n:], it) for p, it in self._tree.items.items() if p.startswith(self._prefix)]

    @dbus.service.method(IFACE, out_signature="v")
    def GetValue(self):
        return dbus.Dictionary({k: wrap(it.value) for k, it in self._under()}, signature="sv", variant_level=1)

    @dbus.service.method(IFACE, out_signature="v")
    def GetText(self):
        return dbus.Dictionary({k: it.text() for k, it in self._under()}, signature="ss", variant_level=1)


class _RootObject(_NodeObject):
    @dbus.service.method(IFACE, out_signature="a{sa{sv}}")
    def GetItems(self):
        return self._tree.snapshot()

    @dbus.service.signal(IFACE, signature="a{sa{sv}}")
    def ItemsChanged(self, changes):
        pass


class ServiceTree:
    """Every path of one service. add() before register(): the bus name is
    taken last, so a consumer that sees the service sees all its paths."""

    def __init__(self, bus, name):
        self.bus = bus
        self.name = name
        self.items = {}
        self._objects = {}
        self._nodes = {}
        self._changed = set()
        self._busname = None
        self._nodes["/"] = _RootObject(self, bus, "/")

    def add(self, path, value=None, fmt=None, on_write=None, description=""):
        item = Item(path, value, fmt, on_write, description)
        self.items[path] = item
        self._objects[path] = _ItemObject(self, self.bus, item)
        parts = path.strip("/").split("/")
        for i in range(1, len(parts)):
            node = "/" + "/".join(parts[:i])
            if node not in self._nodes and node not in self._objects:
                self._nodes[node] = _NodeObject(self, self.bus, node)
        return item

    def register(self):
        self._busname = dbus.service.BusName(self.name, self.bus, do_not_queue=True)

    def __getitem__(self, path):
        return self.items[path].value

    def set(self, path, value):
        """A new value; reaches the bus at the next flush() if it changed."""
        item = self.items[path]
        if isinstance(value, float) and value != value:
            value = None  # NaN is never sent: invalid instead
        if item.value != value or type(item.value) is not type(value):
            item.value = value
            self._changed.add(path)

    def write(self, path, value):
        """SetValue from the bus: 0 = accepted, 1 = refused (read-only, or the
        path's rule said no)."""
        item = self.items[path]
        if item.on_write is None:
            return 1
        if not item.on_write(path, value):
            return 1
        self.set(path, value)
        self.flush()
        return 0

    def snapshot(self):
        return {p: {"Value": wrap(it.value), "Text": dbus.String(it.text(), variant_level=1)}
                for p, it in self.items.items()}

    def flush(self):
        """One PropertiesChanged per changed path and one ItemsChanged on "/"."""
        if not self._changed:
            return
        batch = {}
        for path in sorted(self._changed):
            it = self.items[path]
            change = {"Value": wrap(it.value), "Text": dbus.String(it.text(), variant_level=1)}
            self._objects[path].PropertiesChanged(change)
            batch[path] = change
        self._changed.clear()
        self._nodes["/"].ItemsChanged(batch)
