-- The dissection engine: one interpreter of the layout tables above (MESSAGES and TYPES
-- of RA 3.3, AS4_MESSAGES and AS4_TYPES of AS-4), written once; the tables are generated
-- from the YAML definitions. Nothing here knows a particular message.

local jaus = Proto("jaus", "JAUS (RA 3.3)")
local jaus4 = Proto("jaus4", "JAUS AS-4 (SAE AS5684 message)")
local judp = Proto("judp", "JAUS UDP transport (AS5669)")
local as5669a = Proto("as5669a", "JAUS transport AS5669A (JUDP version 2)")

-- The two generations: their tables, the prefix of their field names, their protocol.
local RA33 = { messages = MESSAGES, types = TYPES, prefix = "jaus", proto = jaus, fields = {} }
local AS4 = { messages = AS4_MESSAGES, types = AS4_TYPES, prefix = "jaus4", proto = jaus4, fields = {} }

local DATA_FLAGS = { [0] = "single", [1] = "first", [2] = "middle", [4] = "retransmission request", [8] = "last" }
local ACK_NAK = { [0] = "none", [1] = "request", [2] = "NAK", [3] = "ACK" }

local hf = {
  properties = ProtoField.uint16("jaus.properties", "Message properties", base.HEX),
  priority = ProtoField.uint16("jaus.priority", "Priority", base.DEC, nil, 0x000F),
  ack_nak = ProtoField.uint16("jaus.ack_nak", "ACK/NAK", base.DEC, ACK_NAK, 0x0030),
  service_connection = ProtoField.bool("jaus.service_connection", "Service connection", 16, nil, 0x0040),
  experimental = ProtoField.bool("jaus.experimental", "Experimental", 16, nil, 0x0080),
  version = ProtoField.uint16("jaus.version", "Version", base.DEC, nil, 0x3F00),
  reserved = ProtoField.uint16("jaus.reserved", "Reserved", base.DEC, nil, 0xC000),
  code = ProtoField.uint16("jaus.command_code", "Command code", base.HEX),
  message = ProtoField.string("jaus.message", "Message"),
  message_id = ProtoField.uint16("jaus.embedded_id", "Embedded message ID", base.HEX),
  embedded_message = ProtoField.string("jaus.embedded_message", "Embedded message"),
  destination = ProtoField.string("jaus.destination", "Destination"),
  source = ProtoField.string("jaus.source", "Source"),
  subsystem = ProtoField.uint8("jaus.address.subsystem", "Subsystem"),
  node = ProtoField.uint8("jaus.address.node", "Node"),
  component = ProtoField.uint8("jaus.address.component", "Component"),
  instance = ProtoField.uint8("jaus.address.instance", "Instance"),
  data_control = ProtoField.uint16("jaus.data_control", "Data control", base.HEX),
  data_size = ProtoField.uint16("jaus.data_size", "Data size", base.DEC, nil, 0x0FFF),
  data_flag = ProtoField.uint16("jaus.data_flag", "Data flag", base.DEC, DATA_FLAGS, 0xF000),
  sequence = ProtoField.uint16("jaus.sequence_number", "Sequence number"),
  presence = ProtoField.uint32("jaus.presence_vector", "Presence vector", base.HEX),
  fragment = ProtoField.uint16("jaus.fragment", "Fragment of a multi-packet message"),
  reassembled = ProtoField.uint32("jaus.reassembled_size", "Reassembled body size"),
  trailing = ProtoField.bytes("jaus.trailing", "Trailing bytes"),
}

local hf_judp = {
  judp_version = ProtoField.uint8("judp.version", "Version"),
  judp_hc_number = ProtoField.uint8("judp.hc_number", "Header compression number"),
  judp_hc_length = ProtoField.uint8("judp.hc_length", "Header compression length", base.DEC, nil, 0xFC),
  judp_hc_flags = ProtoField.uint8("judp.hc_flags", "Header compression flags", base.DEC, nil, 0x03),
  judp_length = ProtoField.uint16("judp.message_length", "Message length"),
  opc_prefix = ProtoField.string("judp.opc_prefix", "JAUS01.0 prefix"),
}
for k, v in pairs(hf_judp) do hf[k] = v end

local ef_malformed = ProtoExpert.new("jaus.malformed", "Malformed JAUS message", expert.group.MALFORMED, expert.severity.ERROR)
local ef_unknown = ProtoExpert.new("jaus.unknown_code", "Command code not in the definitions", expert.group.UNDECODED, expert.severity.NOTE)
local ef_compressed = ProtoExpert.new("judp.compressed", "JUDP header compression is not decoded", expert.group.UNDECODED, expert.severity.WARN)
local ef4_malformed = ProtoExpert.new("jaus4.malformed", "Malformed AS-4 message", expert.group.MALFORMED, expert.severity.ERROR)
local ef4_unknown = ProtoExpert.new("jaus4.unknown_id", "Message ID not in the AS-4 definitions", expert.group.UNDECODED, expert.severity.NOTE)
local ef_as4_malformed = ProtoExpert.new("as5669a.malformed", "Malformed AS5669A message", expert.group.MALFORMED, expert.severity.ERROR)
local ef_as4_compressed = ProtoExpert.new("as5669a.compressed", "AS5669A header compression is not decoded", expert.group.UNDECODED, expert.severity.WARN)

local PRIORITY = { [0] = "low", [1] = "standard", [2] = "high", [3] = "safety critical" }
local BROADCAST = { [0] = "none", [1] = "local", [2] = "global", [3] = "reserved" }
local DATA_CONTROL = { [0] = "single", [1] = "first", [2] = "normal", [3] = "last" }

-- The AS5669A transport header (little-endian throughout).
local hf_as4 = {
  version = ProtoField.uint8("as5669a.version", "Transport version"),
  message_type = ProtoField.uint8("as5669a.message_type", "Message type", base.DEC, nil, 0xFC),
  hc_flags = ProtoField.uint8("as5669a.hc_flags", "Header compression flags", base.DEC, nil, 0x03),
  data_size = ProtoField.uint16("as5669a.data_size", "Data size"),
  hc_number = ProtoField.uint8("as5669a.hc_number", "Header compression number"),
  hc_length = ProtoField.uint8("as5669a.hc_length", "Header compression length"),
  properties = ProtoField.uint8("as5669a.properties", "Properties", base.HEX),
  priority = ProtoField.uint8("as5669a.priority", "Priority", base.DEC, PRIORITY, 0x03),
  broadcast = ProtoField.uint8("as5669a.broadcast", "Broadcast", base.DEC, BROADCAST, 0x0C),
  ack_nak = ProtoField.uint8("as5669a.ack_nak", "ACK/NAK", base.DEC, ACK_NAK, 0x30),
  data_control = ProtoField.uint8("as5669a.data_control", "Data control", base.DEC, DATA_CONTROL, 0xC0),
  destination = ProtoField.string("as5669a.destination", "Destination"),
  source = ProtoField.string("as5669a.source", "Source"),
  sequence = ProtoField.uint16("as5669a.sequence_number", "Sequence number"),
  fragment = ProtoField.bytes("as5669a.fragment", "Fragment of a multi-packet message"),
}
local hf4 = {
  message_id = ProtoField.uint16("jaus4.message_id", "Message ID", base.HEX),
  message = ProtoField.string("jaus4.message", "Message"),
  embedded_message = ProtoField.string("jaus4.embedded_message", "Embedded message"),
  presence = ProtoField.uint32("jaus4.presence_vector", "Presence vector", base.HEX),
  reassembled = ProtoField.uint32("jaus4.reassembled_size", "Reassembled payload size"),
  trailing = ProtoField.bytes("jaus4.trailing", "Trailing bytes"),
}
RA33.hf = hf
AS4.hf = hf4
RA33.ef_malformed = ef_malformed
RA33.ef_unknown = ef_unknown
AS4.ef_malformed = ef4_malformed
AS4.ef_unknown = ef4_unknown

-- Per-field ProtoFields, created from the tables.
local INT = {
  u8 = { size = 1, signed = false, pf = ProtoField.uint8 },
  u16 = { size = 2, signed = false, pf = ProtoField.uint16 },
  u32 = { size = 4, signed = false, pf = ProtoField.uint32 },
  u64 = { size = 8, signed = false, pf = ProtoField.uint64 },
  i8 = { size = 1, signed = true, pf = ProtoField.int8 },
  i16 = { size = 2, signed = true, pf = ProtoField.int16 },
  i32 = { size = 4, signed = true, pf = ProtoField.int32 },
  i64 = { size = 8, signed = true, pf = ProtoField.int64 },
}
local DIVISOR = {
  u8 = 255.0, u16 = 65535.0, u32 = 4294967294.0, i8 = 254.0, i32 = 4294967294.0, i16 = 65534.0,
  u64 = 18446744073709551615.0, i64 = 18446744073709551614.0,
}
local MASKS = { u8 = 0xFF, u16 = 0xFFFF, u32 = 0xFFFFFFFF }

for k, f in pairs(hf) do
  if hf_judp[k] == nil then RA33.fields[#RA33.fields + 1] = f end
end
for _, f in pairs(hf4) do AS4.fields[#AS4.fields + 1] = f end

local function register(d, pf)
  d.fields[#d.fields + 1] = pf
  return pf
end

local function enum_strings(d, tyname)
  local t = d.types[tyname]
  local out = {}
  for _, v in ipairs(t.values or {}) do out[v[2]] = v[1] end
  return out
end

-- Creates the ProtoField(s) a field (or list element) of generation `d` is shown with.
local function make_fields(d, f, abbrev, label)
  local w = f.w
  if w.k == "int" then
    f.pf = register(d, INT[w.int].pf(abbrev, label, base.DEC))
  elseif w.k == "scaled" or w.k == "f64" then
    f.pf = register(d, ProtoField.double(abbrev, label))
  elseif w.k == "f32" then
    f.pf = register(d, ProtoField.float(abbrev, label))
  elseif w.k == "str" then
    f.pf = register(d, ProtoField.string(abbrev, label))
  elseif w.k == "bytes" then
    f.pf = register(d, ProtoField.bytes(abbrev, label))
  elseif w.k == "flag" then
    f.pf = register(d, ProtoField.bool(abbrev, label))
  elseif w.k == "named" then
    local t = d.types[w.name]
    if t.kind == "enum" then
      f.pf = register(d, INT[t.repr].pf(abbrev, label, base.DEC, enum_strings(d, w.name)))
    elseif t.kind == "bitfield" then
      f.pf = register(d, INT[t.repr].pf(abbrev, label, base.HEX))
    elseif t.kind == "union" and w.tag_field == nil then
      local tags = {}
      for _, v in ipairs(t.variants) do tags[v.tag] = v.name end
      f.tag_pf = register(d, INT[t.repr].pf(abbrev .. ".tag", label .. " (variant)", base.DEC, tags))
    end
  elseif w.k == "list" or w.k == "listf" then
    f.elem = { w = w.elem, name = f.name, unit = f.unit }
    make_fields(d, f.elem, abbrev, label)
  end
end

-- The ProtoFields of every type and message of generation `d`; bit-field members get
-- one each, shown under the value.
local function make_all_fields(d)
  for tname, t in pairs(d.types) do
    if t.kind == "bitfield" then
      for _, m in ipairs(t.bits) do
        local abbrev = d.prefix .. "." .. tname .. "." .. m.name
        if m.hi == nil then
          m.pf = register(d, ProtoField.bool(abbrev, m.name))
        else
          m.pf = register(d, ProtoField.uint32(abbrev, m.name))
        end
      end
    elseif t.kind == "record" then
      for _, f in ipairs(t.fields) do make_fields(d, f, d.prefix .. "." .. tname .. "." .. f.name, f.name) end
    elseif t.kind == "union" then
      for _, v in ipairs(t.variants) do
        if v.w ~= nil then
          v.f = { w = v.w, name = v.name }
          make_fields(d, v.f, d.prefix .. "." .. tname .. "." .. v.name, v.name)
        end
      end
    end
  end
  for _, m in pairs(d.messages) do
    for _, f in ipairs(m.fields) do make_fields(d, f, d.prefix .. "." .. m.name .. "." .. f.name, f.name) end
  end
end
make_all_fields(RA33)
make_all_fields(AS4)

jaus.fields = RA33.fields
jaus.experts = { ef_malformed, ef_unknown }
jaus4.fields = AS4.fields
jaus4.experts = { ef4_malformed, ef4_unknown }
local judp_list = {}
for _, f in pairs(hf_judp) do judp_list[#judp_list + 1] = f end
judp.fields = judp_list
judp.experts = { ef_compressed }
local as4_list = {}
for _, f in pairs(hf_as4) do as4_list[#as4_list + 1] = f end
as5669a.fields = as4_list
as5669a.experts = { ef_as4_malformed, ef_as4_compressed }

-- Decoding ---------------------------------------------------------------------------

local Malformed = {}

local function need(off, n, limit, what)
  if off + n > limit then
    error({ Malformed, string.format("%s needs %d bytes at offset %d; the body ends at %d", what, n, off, limit) })
  end
end

local function read_int(tvb, off, int, limit, what)
  local d = INT[int]
  need(off, d.size, limit, what)
  local r = tvb(off, d.size)
  local v
  if int == "u64" then v = r:le_uint64()
  elseif int == "i64" then v = r:le_int64()
  elseif d.signed then v = r:le_int()
  else v = r:le_uint() end
  return v, r
end

local function number_of(v)
  if type(v) == "number" then return v end
  return v:tonumber()
end

local function lookup(scope, name)
  while scope ~= nil do
    local v = scope.vars[name]
    if v ~= nil then return v end
    scope = scope.parent
  end
  return nil
end

local function truthy(v)
  if v == nil or v == false then return false end
  if v == true then return true end
  return number_of(v) ~= 0
end

-- A sub-tvb of `n` bytes at `off` (an empty one of its own when `n` is 0, which a range
-- at the end of a buffer cannot give).
local function sub_tvb(tvb, off, n)
  if n == 0 then return ByteArray.new():tvb("empty") end
  return tvb:range(off, n):tvb()
end

local dissect_value, dissect_fields, dissect_body, dissect_packet, dissect_embedded

-- A string or blob length: returns (start, length on the wire, content length).
local function length_of(tvb, off, len, limit, what)
  if len.k == "fixed" then
    if len.short and off + len.n > limit then return off, limit - off, limit - off end
    need(off, len.n, limit, what)
    return off, len.n, len.n
  elseif len.k == "prefix" then
    local n = number_of((read_int(tvb, off, len.int, limit, what .. " length")))
    local s = INT[len.int].size
    need(off + s, n, limit, what)
    return off + s, s + n, n
  elseif len.k == "rest" then
    return off, limit - off, limit - off
  else -- nul
    for i = off, limit - 1 do
      if tvb(i, 1):uint() == 0 then return off, i - off + 1, i - off end
    end
    error({ Malformed, what .. " has no terminating NUL" })
  end
end

-- One value of wire form `w` at `off`; returns (value for variables, new offset).
dissect_value = function(tvb, off, limit, tree, f, scope, pinfo)
  local w = f.w
  local what = f.name or "value"
  if w.k == "int" then
    local v, r = read_int(tvb, off, w.int, limit, what)
    tree:add_le(f.pf, r)
    return v, off + INT[w.int].size
  elseif w.k == "scaled" then
    local raw, r = read_int(tvb, off, w.int, limit, what)
    local d = INT[w.int]
    local s = (w.hi - w.lo) / DIVISOR[w.int]
    local bias = w.lo
    if d.signed then bias = (w.hi + w.lo) / 2 end
    local value = number_of(raw) * s + bias
    local item = tree:add(f.pf, r, value)
    item:append_text(string.format("%s (raw %s)", f.unit and (" " .. f.unit) or "", tostring(raw)))
    return value, off + d.size
  elseif w.k == "f32" then
    need(off, 4, limit, what)
    local r = tvb(off, 4)
    tree:add_le(f.pf, r)
    return r:le_float(), off + 4
  elseif w.k == "f64" then
    need(off, 8, limit, what)
    local r = tvb(off, 8)
    tree:add_le(f.pf, r)
    return r:le_float(), off + 8
  elseif w.k == "str" then
    local start, wire, n = length_of(tvb, off, w.len, limit, what)
    local text = ""
    if n > 0 then
      text = tvb(start, n):string(ENC_ISO_8859_1)
      local nul = text:find("\0", 1, true)
      if nul ~= nil then text = text:sub(1, nul - 1) end
    end
    if wire > 0 then
      tree:add(f.pf, tvb(off, wire), text)
    else
      tree:add(f.pf, tvb(off, 0), text)
    end
    return text, off + wire
  elseif w.k == "bytes" then
    local start, wire, n = length_of(tvb, off, w.len, limit, what)
    local item
    if n > 0 then item = tree:add(f.pf, tvb(start, n)) else item = tree:add(f.pf, tvb(off, 0)) end
    if f.code_field ~= nil and n > 0 then
      local code = lookup(scope, f.code_field)
      if code ~= nil then
        code = number_of(code)
        if f.complement then
          if code >= 0x4000 then code = code - 0x2000 else code = code + 0x2000 end
        end
        dissect_body(sub_tvb(tvb, start, n), code, item, pinfo, scope.d)
      end
    end
    if f.embeds then dissect_embedded(tvb, start, n, item, f, scope, pinfo) end
    return n, off + wire
  elseif w.k == "flag" then
    return false, off
  elseif w.k == "packet" then
    local start, n = off, 0
    if w.size ~= nil then
      n = number_of((read_int(tvb, off, w.size, limit, what .. " size")))
      start = off + INT[w.size].size
    else
      -- Without a size prefix the embedded header's data size gives the length.
      need(off, 16, limit, what .. " header")
      n = 16 + tvb(off + 12, 2):le_uint() % 0x1000
    end
    need(start, n, limit, what)
    local sub = tree:add(jaus, tvb(start, n), "Embedded message")
    dissect_packet(sub_tvb(tvb, start, n), sub, pinfo, true)
    return nil, start + n
  elseif w.k == "named" then
    local t = scope.d.types[w.name]
    local vlimit = limit
    if w.size ~= nil then
      local n = number_of((read_int(tvb, off, w.size, limit, what .. " size")))
      off = off + INT[w.size].size
      need(off, n, limit, what)
      vlimit = off + n
    end
    if t.kind == "enum" then
      local v, r = read_int(tvb, off, t.repr, vlimit, what)
      tree:add_le(f.pf, r)
      return v, (w.size and vlimit) or (off + INT[t.repr].size)
    elseif t.kind == "bitfield" then
      local v, r = read_int(tvb, off, t.repr, vlimit, what)
      local item = tree:add_le(f.pf, r)
      local n = number_of(v)
      for _, m in ipairs(t.bits) do
        if m.hi == nil then
          item:add(m.pf, r, math.floor(n / 2 ^ m.lo) % 2 == 1)
        else
          local width = m.hi - m.lo + 1
          item:add(m.pf, r, math.floor(n / 2 ^ m.lo) % (2 ^ width))
        end
      end
      return v, (w.size and vlimit) or (off + INT[t.repr].size)
    elseif t.kind == "record" then
      local sub = tree:add(scope.d.proto, tvb(off, 0), f.name or w.name)
      sub:append_text(" (" .. w.name .. ")")
      local start = off
      local inner = { vars = {}, parent = scope, d = scope.d }
      off = dissect_fields(tvb, off, vlimit, sub, t.fields, t.presence, inner, pinfo)
      sub:set_len(off - start)
      return nil, (w.size and vlimit) or off
    else -- union
      local tag
      local sub = tree:add(scope.d.proto, tvb(off, 0), f.name or w.name)
      local start = off
      if w.tag_field ~= nil then
        tag = lookup(scope, w.tag_field)
      else
        local r
        tag, r = read_int(tvb, off, t.repr, vlimit, what .. " tag")
        sub:add_le(f.tag_pf, r)
        off = off + INT[t.repr].size
      end
      tag = number_of(tag or 0)
      local variant = nil
      for _, v in ipairs(t.variants) do if v.tag == tag then variant = v end end
      if variant == nil then
        error({ Malformed, string.format("%s: tag %d names no variant of %s", what, tag, w.name) })
      end
      sub:append_text(": " .. variant.name)
      if variant.f ~= nil then
        local _, o = dissect_value(tvb, off, vlimit, sub, variant.f, { vars = {}, parent = scope, d = scope.d }, pinfo)
        off = o
      end
      sub:set_len(off - start)
      return tag, (w.size and vlimit) or off
    end
  elseif w.k == "list" or w.k == "listf" then
    local count
    local start = off
    if w.k == "list" and w.count ~= nil then
      local c = read_int(tvb, off, w.count, limit, what .. " count")
      count = number_of(c)
      off = off + INT[w.count].size
    elseif w.k == "listf" then
      local c = lookup(scope, w.field)
      count = number_of(c or 0) - (w.minus or 0)
      if count < 0 then count = 0 end
    end
    local sub = tree:add(scope.d.proto, tvb(start, 0), f.name or "list")
    local i = 0
    while (count ~= nil and i < count) or (count == nil and off < limit) do
      local _, o = dissect_value(tvb, off, limit, sub, f.elem, scope, pinfo)
      off = o
      i = i + 1
    end
    sub:append_text(string.format(" (%d elements)", i))
    sub:set_len(off - start)
    return i, off
  end
  error({ Malformed, "unknown wire form " .. tostring(w.k) })
end

-- The fields of a message or record: presence vector first when there is one.
dissect_fields = function(tvb, off, limit, tree, fields, presence, scope, pinfo)
  local pv = nil
  local pv_range = nil
  if presence ~= nil then
    local v
    v, pv_range = read_int(tvb, off, presence, limit, "presence vector")
    pv = number_of(v)
    tree:add_le(scope.d.hf.presence, pv_range, pv)
    off = off + INT[presence].size
  end
  for _, f in ipairs(fields) do
    local present = true
    if f.w.k == "flag" then
      local set = pv ~= nil and math.floor(pv / 2 ^ f.bit) % 2 == 1
      scope.vars[f.name] = set
      if pv_range ~= nil then tree:add(f.pf, pv_range, set) end
      present = false
    elseif f.bit ~= nil then
      present = pv ~= nil and math.floor(pv / 2 ^ f.bit) % 2 == 1
    elseif f.present_if ~= nil then
      present = truthy(lookup(scope, f.present_if))
    end
    if present then
      local v, o = dissect_value(tvb, off, limit, tree, f, scope, pinfo)
      scope.vars[f.name] = v
      off = o
    end
  end
  return off
end

-- A message body of command code (message ID) `code` of generation `d` into `tree`.
dissect_body = function(body, code, tree, pinfo, d)
  local m = d.messages[code]
  if m == nil then
    tree:add_proto_expert_info(d.ef_unknown)
    return
  end
  tree:append_text(": " .. m.name)
  local ok, err = pcall(function()
    local off = dissect_fields(body, 0, body:len(), tree, m.fields, m.presence, { vars = {}, d = d }, pinfo)
    if off < body:len() then
      tree:add(d.hf.trailing, body(off, body:len() - off))
    end
  end)
  if not ok then
    local text = err
    if type(err) == "table" and err[1] == Malformed then text = err[2] end
    tree:add_proto_expert_info(d.ef_malformed, m.name .. ": " .. tostring(text))
  end
end

-- A message carried in the `n` bytes at `start` of field `f` (`embeds: message`): its
-- 16-bit message ID, then its body; only when the field's `embeds_if` condition holds.
dissect_embedded = function(tvb, start, n, item, f, scope, pinfo)
  if f.embeds_if ~= nil then
    local v = lookup(scope, f.embeds_if.field)
    if v == nil or number_of(v) ~= f.embeds_if.value then return end
  end
  local d = scope.d
  if n < 2 then
    error({ Malformed, string.format("%s holds a message but has %d bytes, fewer than its 2-byte message ID", f.name, n) })
  end
  local id = tvb(start, 2):le_uint()
  local sub = item:add(d.proto, tvb(start, n), "Embedded message")
  sub:add_le(d.hf.message_id, tvb(start, 2))
  local m = d.messages[id]
  if m ~= nil then sub:add(d.hf.embedded_message, tvb(start, 2), m.name) end
  dissect_body(sub_tvb(tvb, start + 2, n - 2), id, sub, pinfo, d)
end

local function address(tvb, off)
  local r = tvb(off, 4)
  return string.format("%d.%d.%d.%d", tvb(off + 3, 1):uint(), tvb(off + 2, 1):uint(), tvb(off + 1, 1):uint(), tvb(off, 1):uint()), r
end

-- Multi-packet messages: the parts seen on the first pass, keyed by source, destination
-- and command code; the whole body kept for the frame of the last part.
local parts = {}
local whole = {}

-- One JAUS packet (16-byte header + body) into `tree`.
dissect_packet = function(tvb, tree, pinfo, embedded)
  if tvb:len() < 16 then
    tree:add_proto_expert_info(ef_malformed, string.format("%d bytes: shorter than the 16-byte header", tvb:len()))
    return
  end
  local props = tvb(0, 2)
  local p = tree:add_le(hf.properties, props)
  for _, k in ipairs({ "priority", "ack_nak", "service_connection", "experimental", "version", "reserved" }) do
    p:add_le(hf[k], props)
  end
  local code = tvb(2, 2):le_uint()
  local m = MESSAGES[code]
  local ci = tree:add_le(hf.code, tvb(2, 2))
  if m ~= nil then
    ci:append_text(" (" .. m.title .. ")")
    tree:add(hf.message, tvb(2, 2), m.name)
  end
  local dst, dr = address(tvb, 4)
  local src, sr = address(tvb, 8)
  for _, a in ipairs({ { hf.destination, dst, dr, 4 }, { hf.source, src, sr, 8 } }) do
    local item = tree:add(a[1], a[3], a[2])
    item:add(hf.subsystem, tvb(a[4] + 3, 1))
    item:add(hf.node, tvb(a[4] + 2, 1))
    item:add(hf.component, tvb(a[4] + 1, 1))
    item:add(hf.instance, tvb(a[4], 1))
  end
  local dc = tvb(12, 2)
  local d = tree:add_le(hf.data_control, dc)
  d:add_le(hf.data_size, dc)
  d:add_le(hf.data_flag, dc)
  local size = dc:le_uint() % 0x1000
  local flag = math.floor(dc:le_uint() / 0x1000)
  local seq = tvb(14, 2):le_uint()
  tree:add_le(hf.sequence, tvb(14, 2))
  if 16 + size > tvb:len() then
    tree:add_proto_expert_info(ef_malformed, string.format("data size %d but %d body bytes", size, tvb:len() - 16))
    return
  end
  local name = (m and m.name) or string.format("0x%04X", code)
  if not embedded then
    pinfo.cols.info:append(string.format("%s %s → %s  ", name, src, dst))
  end
  local body = tree:add(jaus, tvb(16, size), "Body")
  if flag == 0 then
    dissect_body(sub_tvb(tvb, 16, size), code, body, pinfo, RA33)
    return
  end
  -- A part of a multi-packet message.
  body:add(hf.fragment, tvb(14, 2), seq)
  local key = src .. ">" .. dst .. "#" .. code
  if not pinfo.visited then
    if flag == 1 then parts[key] = {} end
    local list = parts[key]
    if list ~= nil and (flag == 1 or flag == 2 or flag == 8) then
      list[seq] = tvb:range(16, size):bytes()
      if flag == 8 then
        local all = ByteArray.new()
        local ok = true
        for i = 0, seq do
          if list[i] == nil then ok = false break end
          all:append(list[i])
        end
        if ok then whole[pinfo.number] = all end
        parts[key] = nil
      end
    end
  end
  local all = whole[pinfo.number]
  if all ~= nil then
    local t = all:tvb("Reassembled JAUS body")
    local r = tree:add(jaus, t(), "Reassembled body")
    r:add(hf.reassembled, t(), all:len())
    dissect_body(t, code, r, pinfo, RA33)
  else
    body:append_text(string.format(" (part %d of a multi-packet %s)", seq, name))
  end
end

-- AS5669A (JUDP version 2) ------------------------------------------------------------

-- An AS-4 id: u32 little-endian, subsystem << 16 | node << 8 | component.
local function as4_id(tvb, off)
  local v = tvb(off, 4):le_uint()
  return string.format("%d.%d.%d", math.floor(v / 65536), math.floor(v / 256) % 256, v % 256)
end

-- Multi-packet AS-4 messages: the packets seen on the first pass, keyed by source and
-- destination (first, normal and last packets carry consecutive sequence numbers); the
-- whole payload kept for the frame and message index of the last packet.
local as4_parts = {}
local as4_whole = {}

-- One AS-4 payload (message ID, then the body) into `tree`.
local function dissect_as4_payload(tvb, tree, pinfo, src, dst)
  if tvb:len() < 2 then
    tree:add_proto_expert_info(ef4_malformed, string.format("%d bytes: no room for the 2-byte message ID", tvb:len()))
    return
  end
  local id = tvb(0, 2):le_uint()
  local m = AS4_MESSAGES[id]
  local t = tree:add(jaus4, tvb(), "AS-4 message")
  local ii = t:add_le(hf4.message_id, tvb(0, 2))
  if m ~= nil then
    ii:append_text(" (" .. m.title .. ")")
    t:add(hf4.message, tvb(0, 2), m.name)
  end
  pinfo.cols.info:append(string.format("%s %s → %s  ", (m and m.name) or string.format("0x%04X", id), src, dst))
  dissect_body(sub_tvb(tvb, 2, tvb:len() - 2), id, t, pinfo, AS4)
end

-- One message of an AS5669A datagram at `off` (the `index`-th); returns its end, or nil
-- when the rest of the datagram cannot be read.
local function dissect_as4_message(tvb, off, index, pinfo, tree)
  local avail = tvb:len() - off
  local t = tree:add(as5669a, tvb(off, avail), string.format("Message %d", index))
  if avail < 14 then
    t:add_proto_expert_info(ef_as4_malformed, string.format("%d bytes: shorter than a header and sequence number (14)", avail))
    return nil
  end
  local b0 = tvb(off, 1):uint()
  t:add(hf_as4.message_type, tvb(off, 1))
  t:add(hf_as4.hc_flags, tvb(off, 1))
  local size = tvb(off + 1, 2):le_uint()
  t:add_le(hf_as4.data_size, tvb(off + 1, 2))
  if math.floor(b0 / 4) ~= 0 then
    t:add_proto_expert_info(ef_as4_malformed, string.format("message type %d is not a JAUS message (0)", math.floor(b0 / 4)))
    return nil
  end
  local hc = b0 % 4
  if hc >= 2 then
    t:add_proto_expert_info(ef_as4_compressed)
    return nil
  end
  local p = off + 3
  if hc == 1 then
    t:add(hf_as4.hc_number, tvb(p, 1))
    t:add(hf_as4.hc_length, tvb(p + 1, 1))
    p = p + 2
  end
  local header = p + 9 - off
  if size < header + 2 or size > avail then
    t:add_proto_expert_info(ef_as4_malformed, string.format("data size %d: the message needs %d to %d bytes", size, header + 2, avail))
    return nil
  end
  t:set_len(size)
  local props = tvb(p, 1)
  local pi = t:add(hf_as4.properties, props)
  for _, k in ipairs({ "priority", "broadcast", "ack_nak", "data_control" }) do pi:add(hf_as4[k], props) end
  local pv = props:uint()
  local ack = math.floor(pv / 16) % 4
  local dc = math.floor(pv / 64)
  local dst = as4_id(tvb, p + 1)
  local src = as4_id(tvb, p + 5)
  t:add(hf_as4.destination, tvb(p + 1, 4), dst)
  t:add(hf_as4.source, tvb(p + 5, 4), src)
  local seq = tvb(off + size - 2, 2):le_uint()
  t:add_le(hf_as4.sequence, tvb(off + size - 2, 2))
  local plen = size - header - 2
  local payload = sub_tvb(tvb, off + header, plen)
  if dc == 0 then
    if plen == 0 and ack >= 2 then
      t:append_text(string.format(": %s of sequence number %d", ACK_NAK[ack], seq))
      pinfo.cols.info:append(string.format("%s %s → %s  ", ACK_NAK[ack], src, dst))
    else
      dissect_as4_payload(payload, t, pinfo, src, dst)
    end
    return off + size
  end
  -- A packet of a multi-packet message.
  if plen > 0 then t:add(hf_as4.fragment, tvb(off + header, plen)) end
  local key = src .. ">" .. dst
  if not pinfo.visited then
    if dc == 1 then as4_parts[key] = { first = seq, bytes = {} } end
    local list = as4_parts[key]
    if list ~= nil then
      list.bytes[(seq - list.first) % 65536] = payload:bytes()
      if dc == 3 then
        local all = ByteArray.new()
        local ok = true
        for i = 0, (seq - list.first) % 65536 do
          if list.bytes[i] == nil then ok = false break end
          all:append(list.bytes[i])
        end
        if ok then as4_whole[pinfo.number .. ":" .. index] = all end
        as4_parts[key] = nil
      end
    end
  end
  local all = as4_whole[pinfo.number .. ":" .. index]
  if all ~= nil then
    local whole = all:tvb("Reassembled AS-4 payload")
    local r = t:add(jaus4, whole(), "Reassembled payload")
    r:add(hf4.reassembled, whole(), all:len())
    dissect_as4_payload(whole, r, pinfo, src, dst)
  else
    t:append_text(string.format(" (%s packet of a multi-packet message, sequence number %d)", DATA_CONTROL[dc], seq))
  end
  return off + size
end

-- An AS5669A datagram: the version byte 2, then one or more messages.
local function dissect_as5669a(tvb, pinfo, tree)
  pinfo.cols.protocol = "JAUS AS-4"
  local t = tree:add(as5669a, tvb())
  t:add(hf_as4.version, tvb(0, 1))
  local off, index = 1, 0
  while off < tvb:len() do
    off = dissect_as4_message(tvb, off, index, pinfo, t)
    if off == nil then break end
    index = index + 1
  end
  return tvb:len()
end

function jaus.dissector(tvb, pinfo, tree)
  pinfo.cols.protocol = "JAUS"
  local t = tree:add(jaus, tvb())
  dissect_packet(tvb, t, pinfo, false)
  return tvb:len()
end

function judp.dissector(tvb, pinfo, tree)
  if tvb:len() < 1 then return 0 end
  pinfo.cols.info:clear()
  if tvb(0, 1):uint() == 2 then return dissect_as5669a(tvb, pinfo, tree) end
  pinfo.cols.protocol = "JAUS"
  local t = tree:add(judp, tvb())
  if tvb:len() >= 8 and tvb(0, 8):string() == "JAUS01.0" then
    t:add(hf.opc_prefix, tvb(0, 8))
    local sub = tree:add(jaus, tvb(8))
    dissect_packet(tvb:range(8):tvb(), sub, pinfo, false)
    return tvb:len()
  end
  t:add(hf.judp_version, tvb(0, 1))
  local off = 1
  while off + 4 <= tvb:len() do
    t:add(hf.judp_hc_number, tvb(off, 1))
    t:add(hf.judp_hc_length, tvb(off + 1, 1))
    t:add(hf.judp_hc_flags, tvb(off + 1, 1))
    local flags = tvb(off + 1, 1):uint() % 4
    local n = tvb(off + 2, 2):uint()
    t:add(hf.judp_length, tvb(off + 2, 2))
    off = off + 4
    if flags >= 2 then
      t:add_proto_expert_info(ef_compressed)
      return tvb:len()
    end
    if off + n > tvb:len() then n = tvb:len() - off end
    local sub = tree:add(jaus, tvb(off, n))
    dissect_packet(tvb:range(off, n):tvb(), sub, pinfo, false)
    off = off + n
  end
  return tvb:len()
end

DissectorTable.get("udp.port"):add(JAUS_UDP_PORT, judp)

-- On other ports: a datagram that is one whole JUDP message (version 1, uncompressed,
-- a length that covers a header of version 2 whose data size fills the rest) or starts
-- with "JAUS01.0".
local function looks_like_jaus(tvb)
  local n = tvb:len()
  if n >= 15 and tvb(0, 1):uint() == 2 then
    -- AS5669A: JAUS messages without header compression filling the datagram exactly.
    local off = 1
    while off < n do
      if n - off < 14 or tvb(off, 1):uint() >= 2 then return false end
      local size = tvb(off + 1, 2):le_uint()
      if size < 14 + tvb(off, 1):uint() * 2 or off + size > n then return false end
      off = off + size
    end
    return true
  end
  if n >= 24 and tvb(0, 8):string() == "JAUS01.0" then
    return tvb(8 + 12, 2):le_uint() % 0x1000 + 24 == n
  end
  if n < 21 or tvb(0, 1):uint() ~= 1 or tvb(2, 1):uint() % 4 >= 2 then return false end
  local len = tvb(3, 2):uint()
  if len < 16 or 5 + len ~= n then return false end
  local version = math.floor(tvb(5, 2):le_uint() / 256) % 64
  local size = tvb(5 + 12, 2):le_uint() % 0x1000
  return version == 2 and 16 + size == len
end

judp:register_heuristic("udp", function(tvb, pinfo, tree)
  if not looks_like_jaus(tvb) then return false end
  judp.dissector(tvb, pinfo, tree)
  return true
end)
