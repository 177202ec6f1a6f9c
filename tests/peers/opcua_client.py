"""An independent OPC UA client (python asyncua) for drivegen-cli/tests/gateway_opcua.rs.

  opcua_client.py cert DIR          make the client's key and certificate (DER) in DIR
  opcua_client.py untrusted URL DIR try the secure endpoint before the server trusts the client
  opcua_client.py check URL DIR     browse, read, write, subscribe; print what it saw as JSON
  opcua_client.py status URL NODE   read one variable anonymously; print its status as JSON

The checks print facts (values, status code names); the Rust test asserts on them. Passwords
come from OPERATOR_PASSWORD and VIEWER_PASSWORD.
"""

import asyncio
import json
import os
import sys
from pathlib import Path

from asyncua import Client, ua
from asyncua.crypto.cert_gen import setup_self_signed_certificate
from asyncua.crypto.security_policies import SecurityPolicyBasic256Sha256
from cryptography.x509.oid import ExtendedKeyUsageOID

APP_URI = "urn:drivegen:test-client"
NAMESPACE = "urn:drivegen:gateway"


def paths(folder):
    folder = Path(folder)
    return folder / "client-key.pem", folder / "client.der"


async def make_cert(folder):
    key, cert = paths(folder)
    await setup_self_signed_certificate(
        key, cert, APP_URI, "localhost", [ExtendedKeyUsageOID.CLIENT_AUTH], {"commonName": "drivegen test client"}
    )
    print(cert)


def status_name(error):
    return type(error).__name__


async def write(node, value, variant_type):
    """The status of a write: `Good` or the Bad code's name."""
    try:
        await node.write_value(ua.DataValue(ua.Variant(value, variant_type)))
        return "Good"
    except ua.UaStatusCodeError as e:
        return status_name(e)


async def secure_client(url, folder, user, password):
    key, cert = paths(folder)
    client = Client(url, timeout=10)
    client.application_uri = APP_URI
    await client.set_security(
        SecurityPolicyBasic256Sha256, str(cert), str(key), mode=ua.MessageSecurityMode.SignAndEncrypt
    )
    client.set_user(user)
    client.set_password(password)
    return client


async def value_of(node):
    dv = await node.read_data_value(raise_on_bad_status=False)
    return dv.Value.Value if dv.Value is not None else None


async def wait_for(node, wanted, seconds=10):
    for _ in range(seconds * 10):
        if await value_of(node) == wanted:
            return True
        await asyncio.sleep(0.1)
    return False


class Changes:
    def __init__(self):
        self.values = []

    def datachange_notification(self, node, value, data):
        self.values.append(value)


async def check(url, folder):
    seen = {}
    # Anonymous, on the endpoint without security: browse and read, never write.
    async with Client(url, timeout=10) as client:
        ns = await client.get_namespace_index(NAMESPACE)
        node = lambda name: client.get_node(ua.NodeId(name, ns))
        folders = await client.nodes.objects.get_children()
        seen["folders"] = sorted([(await f.read_browse_name()).Name for f in folders if f.nodeid.NamespaceIndex == ns])
        lafert = client.get_node(ua.NodeId("lafert", ns))
        seen["lafert_variables"] = sorted([(await v.read_browse_name()).Name for v in await lafert.get_children()])
        for name in ["lafert.bus_dc_link", "lafert.speed_ramp_up", "lafert.operation_mode", "lenze.acceleration_time", "lenze.current_limit"]:
            variable = node(name)
            # The first poll may still be on its way.
            for _ in range(50):
                dv = await variable.read_data_value(raise_on_bad_status=False)
                if dv.StatusCode.is_good():
                    break
                await asyncio.sleep(0.1)
            data_type = await variable.read_data_type()
            facts = {
                "value": dv.Value.Value,
                "type": ua.ObjectIdNames[data_type.Identifier],
                "status": dv.StatusCode.name,
                "has_source_time": dv.SourceTimestamp is not None,
                "access": (await variable.read_attribute(ua.AttributeIds.AccessLevel)).Value.Value,
                "user_access": (await variable.read_attribute(ua.AttributeIds.UserAccessLevel)).Value.Value,
            }
            for prop in ["EngineeringUnits", "EURange", "EnumValues"]:
                try:
                    v = await (await variable.get_child(f"0:{prop}")).read_value()
                except ua.UaError:
                    continue
                if prop == "EngineeringUnits":
                    facts["unit"] = {"name": v.DisplayName.Text, "id": v.UnitId, "ns": v.NamespaceUri}
                elif prop == "EURange":
                    facts["range"] = [v.Low, v.High]
                else:
                    facts["enum"] = {e.DisplayName.Text: e.Value for e in v}
            seen[name] = facts
        seen["anonymous_write"] = await write(node("lafert.speed_ramp_up"), 1000, ua.VariantType.UInt16)

    # The operator, signed and encrypted, with a password: writes land or are refused.
    operator = await secure_client(url, folder, "operator", os.environ["OPERATOR_PASSWORD"])
    async with operator as client:
        ns = await client.get_namespace_index(NAMESPACE)
        node = lambda name: client.get_node(ua.NodeId(name, ns))
        ramp = node("lafert.speed_ramp_up")
        changes = Changes()
        subscription = await client.create_subscription(100, changes)
        await subscription.subscribe_data_change(ramp)
        writes = {
            "ramp_1500": await write(ramp, 1500, ua.VariantType.UInt16),
            "ramp_out_of_range": await write(ramp, 40000, ua.VariantType.UInt16),
            "ramp_wrong_type": await write(ramp, 1500.0, ua.VariantType.Double),
            "mode_torque": await write(node("lafert.operation_mode"), 1, ua.VariantType.UInt16),
            "mode_unknown": await write(node("lafert.operation_mode"), 99, ua.VariantType.UInt16),
            "lenze_accel": await write(node("lenze.acceleration_time"), 12.5, ua.VariantType.Double),
            "lenze_accel_out_of_range": await write(node("lenze.acceleration_time"), 1000.0, ua.VariantType.Double),
            "lenze_current_limit": await write(node("lenze.current_limit"), 100, ua.VariantType.UInt16),
        }
        seen["operator_writes"] = writes
        seen["ramp_read_back"] = await wait_for(ramp, 1500) and 1500
        seen["accel_after"] = await value_of(node("lenze.acceleration_time"))
        # The subscription sees the write at the next poll.
        for _ in range(100):
            if 1500 in changes.values:
                break
            await asyncio.sleep(0.1)
        seen["subscription_values"] = changes.values
        await subscription.delete()

    # The viewer logs in the same way and may not write.
    viewer = await secure_client(url, folder, "viewer", os.environ["VIEWER_PASSWORD"])
    async with viewer as client:
        ns = await client.get_namespace_index(NAMESPACE)
        ramp = client.get_node(ua.NodeId("lafert.speed_ramp_up", ns))
        seen["viewer_read"] = await value_of(ramp)
        seen["viewer_write"] = await write(ramp, 1000, ua.VariantType.UInt16)

    # A wrong password does not get in.
    wrong = await secure_client(url, folder, "operator", "not-the-password")
    try:
        async with wrong:
            seen["wrong_password"] = "connected"
    except Exception as e:  # the refusal's type differs between asyncua versions
        seen["wrong_password"] = status_name(e)
    print(json.dumps(seen))


async def untrusted(url, folder):
    client = await secure_client(url, folder, "operator", os.environ["OPERATOR_PASSWORD"])
    try:
        async with client:
            outcome = "connected"
    except Exception as e:  # BadSecurityChecksFailed, or the connection closed
        outcome = status_name(e)
    print(json.dumps({"secure": outcome}))


async def status(url, name):
    async with Client(url, timeout=10) as client:
        ns = await client.get_namespace_index(NAMESPACE)
        dv = await client.get_node(ua.NodeId(name, ns)).read_data_value(raise_on_bad_status=False)
        print(json.dumps({"status": dv.StatusCode.name, "value": dv.Value.Value if dv.Value is not None else None}))


if __name__ == "__main__":
    mode, args = sys.argv[1], sys.argv[2:]
    run = {"cert": make_cert, "untrusted": untrusted, "check": check, "status": status}[mode]
    asyncio.run(run(*args))
