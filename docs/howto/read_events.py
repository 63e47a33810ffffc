"""Read a run's events.csv (how-to): impacts per contact, the hardest one, flight times.

usage: python3 docs/howto/read_events.py RUN_DIR
"""
import csv
import math
import sys
from collections import defaultdict

run_dir = sys.argv[1]
with open(f"{run_dir}/events.csv") as f:
    events = list(csv.DictReader(f))          # one dict per event, keys from the header

print("columns:", ", ".join(events[0].keys()) if events else "(no events)")
by_contact = defaultdict(lambda: defaultdict(int))
for e in events:
    by_contact[e.get("contact", "")][e["kind"]] += 1
for contact, kinds in by_contact.items():
    print(f"contact {contact or '(single follower)'}: {dict(kinds)}")

impacts = [e for e in events if e["kind"] == "impact"]
if impacts:
    hardest = max(impacts, key=lambda e: float(e["impact_velocity"]))
    cam_deg = math.degrees(float(hardest["theta"])) % 360.0   # theta: cam angle [rad], as history.csv
    print(f"hardest impact: {float(hardest['impact_velocity']):.3f} m/s on "
          f"{hardest.get('contact', 'the cam')} at t = {float(hardest['t']):.6f} s, "
          f"cam angle {cam_deg:.1f} deg, impulse {float(hardest['impulse']):.3g} N·s")

# Flights: from each separation of a contact to its next impact on the same contact.
open_since, flights = {}, defaultdict(list)
for e in events:
    c = e.get("contact", "")
    if e["kind"] == "separation":
        open_since[c] = float(e["t"])
    elif e["kind"] == "impact" and c in open_since:
        flights[c].append(float(e["t"]) - open_since.pop(c))
for c, f in flights.items():
    print(f"{c or 'follower'}: {len(f)} flights, longest {1e3 * max(f):.3f} ms")
