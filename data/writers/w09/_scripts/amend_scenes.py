# Hand-written extra detection lines for training scenes that came out shorter than the
# brief's 80-word floor. Neutral details only (no change to the deciding fact or label).
# Keys are pair ids (applied to both rows) or row ids. Run after train_01..09.
import csv
P = "/work/main/data/writers/w09/train.csv"
X = {
"w09-0072": ["- carpet: dry, patterned, no stains", "- lighting: 100 %, corridor clear", "- room_305: door open, TV on, adult_1's bag on bed", "- OCR lift panel: \"3\" ; OCR ice machine: \"Cleaned 06:00\""],
"w09-0078": ["[10:31:04] det kettle off, 30 C; tea mug on table", "[10:31:05] det walking stick hooked on sofa arm", "[10:31:05] det person_2 none; front door closed", "[10:31:05] det floor dry, rug edge taped down"],
"w09-p054": ["    - corridor_carpet: {state: dry, clear}", "    - exit_sign: {ocr: \"FIRE ESCAPE ->\", lit: true}", "    - room_207: {door: closed, DND: false}", "  lighting: 100 %"],
"w09-0109": ["  flowers: vase on windowsill, water fresh", "  iv_line: capped, not running", "  call_bell: clipped to pillow", "  curtains: drawn around bed, lights at 60 %", "  lanyard_ocr: \"VISITOR - Ward 7 - daughter\""],
"w09-0115": ["- changing_table: 2.5 m from cot_2, nappy bag open", "- window: closed, restrictor fitted", "- floor: soft play mat, clean", "- OCR wall chart: \"Nap times: 12:00-14:00\"", "- audio: carer humming, infant babbling"],
"w09-0120": ["- tv: on, cartoons", "- floor: clean, one rice cake crumb", "- cat: asleep on windowsill", "- remote_cover: on table beside batteries", "- OCR battery pack: \"KEEP OUT OF REACH OF CHILDREN - swallowing can cause serious injury\""],
"w09-p063": ["  shed_light: ON, bright", "  floor: dry concrete, grass clippings", "  dog: none in shed", "  radio: on bench, playing"],
"w09-0147": ["[0.87] clock: OCR \"21:12\"", "[0.86] dog: labrador asleep under table", "[0.85] dishwasher: open, half loaded", "[0.84] OCR school planner on table: \"Year 9 - Maths homework due Wed\""],
"w09-0150": ["  room_state: {lights: bedside lamp on, tv: off, curtains: closed}", "  water_glass: {pos: bathroom shelf, clean}", "  kettle: {pos: desk, cold}", "  floor: {state: dry, suitcase open by wardrobe}"],
"w09-0152": ["- window: closed, blind half down", "- rabbit_hay_rack: full", "- lamp: on side table, shade warm (thermal 41 C)", "- coffee_table: mug, remote, magazine", "- OCR cable guard box: \"split wrap - fit over any flex\""],
"w09-0153": ["  patient_posture: sitting up in bed, arms crossed, shaking head", "  nurse_in_charge: at station, 10 m", "  ng_tube_pack_ocr: \"Fine bore NG tube - adult\"", "  patient_transcript: \"I said no. I don't want it.\"", "  curtains: half drawn"],
"w09-0157": ["- bench_3: glassware drying, inverted beakers", "- window blinds: up, late sun", "- clock: OCR \"15:40\"", "- lost_property_tray: empty, by door", "- student_1 posture: leaning over bag, looking at door"],
"w09-0158": ["[12:01:46] det back door open, garden visible, person_1 on path", "[12:01:47] det kettle cold; fruit bowl; radio off", "[12:01:47] det floor dry", "[12:01:47] det smoke alarm LED green"],
"w09-p083": ["  window: closed, catch OCR \"open for ventilation\"", "  students: none (before school)", "  nitrile_gloves: box on bench", "  bench_surface: smooth laminate, no cracks"],
"w09-0188": ["  chair: pressure cushion, OCR \"Repose\"", "  hoist: parked in corridor, battery green", "  patient_skin_note_ocr: \"Sacral redness worse 30/11\"", "  call_bell: clipped to chair arm", "  window: open 5 cm"],
"w09-0190": ["[18:02:20] det fish: neon tetras x8, platies x4, swimming normally", "[18:02:20] det algae_scraper magnetic, in cabinet drawer", "[18:02:21] det child none; cat asleep on sofa", "[18:02:21] det aquarium light ON, filter running"],
"w09-0191": ["  bed: made, fresh linen", "  bin: emptied", "  room_lights: on", "  housekeeper: {age_est: \"30-40\", pos: bathroom, cleaning}", "  wardrobe: empty apart from safe and spare hangers"],
"w09-0192": ["paint_tin: {ocr: \"Masonry Paint - White\", lid off}", "roller_tray: {pos: decking, roller loaded}", "garden: {lawn: wet, dog: indoors}"],
"w09-0198": ["  [0.87] vivarium_thermometer: OCR cool end \"22 C\"", "  [0.86] window: closed, radiator off", "  [0.85] adult_1: est. 40-50 y, on sofa with tea", "  [0.84] water_dish: shallow, clean"],
"w09-0200": ["    - trolley: {pos: by chute, minibar stock boxes}", "    - floor: {state: dry, lino}", "    - lighting: 100 %", "    - chute_sign_ocr: \"NO BOTTLES - NO SHARPS - NO BAGS OVER 10 kg\"", "    - linen_bag_weight_est: 6 kg"],
"w09-p093": ["  snack_box: {ocr: \"Park snacks - nut free\", contents: [rice cakes, apple slices]}", "  weather_ocr_app: \"12 C, dry\"", "  sun_cream: {pos: shelf}", "  children_state: \"lining up at door with coats on\""],
"w09-p096": ["  [0.89] knife_block slot: empty slot labelled \"CARVING\"", "  [0.88] dog: in garden (door glass)", "  [0.87] floor: dry, tiled", "  [0.86] gravy_jug: on table, warm"],
"w09-0229": ["  room_temp_ocr: \"19 C\"", "  other_cots: {cot_1: empty, cot_2: toddler asleep, bedding: fitted sheet only}", "  baby_monitor: {led: green}", "  lights: dimmed"],
"w09-0230": ["  [0.88] window: open 5 cm, morning light", "  [0.87] dog_ramp: by sofa", "  [0.86] cat: none", "  [0.85] vet_note_ocr fridge: \"Bramble - arthritis - meloxicam 1 ml once daily\""],
"w09-0232": [" 12:40:03 det sink_sign OCR \"NOTHING DOWN THE SINK EXCEPT WATER\"", " 12:40:04 det fume cupboard ON, sash 20 cm", " 12:40:04 det room: students gone, lights on", " 12:40:04 det funnel on bench, clean"],
"w09-0233": ["  patient_pain_score_ocr: \"8/10 at 10:15\"", "  wristband_ocr: \"CARR, Daniel - ALLERGIES: NONE KNOWN\"", "  water_cup: on table", "  cd_register: open at station, 2 signatures 10:18"],
"w09-p101": ["  corridor: {lighting: normal, floor: dry}", "  lift_display_ocr: \"1\"", "  teddy_tag_ocr: \"Property of ISLA\"", "  other_guests: {count: 2, pos: \"at reception queue\"}"],
"w09-p102": ["  [0.87] hedge: privet, half cut, outside door", "  [0.86] workbench: clear apart from cutter", "  [0.85] sun: bright, shed door open", "  [0.84] audio: two-stroke engine, 7800 rpm"],
"w09-p103": ["    - tv: on, late news, volume low", "    - blanket: wool, over his legs", "    - door_hall: open, stairs visible", "  window: closed; radiator on"],
"w09-p104": ["  [0.89] fridge: open, milk on shelf", "  [0.88] window: open, sunny", "  [0.87] blender_label OCR: \"Always unplug before cleaning or clearing blades\"", "  [0.86] floor: dry, school bag by door"],
"w09-p105": ["  det floor: dry, clear, no students yet", "  det other cylinders: none", "  det cylinder_label OCR: \"Secure upright at all times\"", "  det prep_room_door: open to lab"],
"w09-p109": ["  [0.87] run_contents: hay, water bottle full, hide house", "  [0.86] sofa: throw, cushions", "  [0.85] tv: off", "  [0.84] rug: hay scattered near run gate"],
"w09-0268": ["  fridge: {pos: kitchenette, door closed, ocr: \"Milk / teething rings only\"}", "  other_children: {count: 3, activity: \"playing with blocks\"}", "  room_temp_ocr: \"21 C\"", "  carer_2: {age_est: \"40-50\", pos: \"changing area\"}"],
"w09-0270": ["- corridor: dry, lights on, trolley brake on", "- OCR room number plate: \"311\"", "- guest_311 posture: standing in doorway, holding kettle", "- trolley_top: towels, toiletries, sealed glasses"],
"w09-0271": [" det window blinds down; lab lights on", " det other students: 3, packing bags at back", " det cupboard_sign OCR \"Radiation warning trefoil - Key holder: Mr Obi\"", " det clock OCR \"13:55\""],
"w09-0272": ["[07:45:12] det seed packets OCR \"Runner beans\", \"Sweet peas\"", "[07:45:13] det metal bin outside door, lid on", "[07:45:13] det work gloves on bench, pair", "[07:45:13] det floor dry, sunny"],
"w09-0273": ["  [0.87] bath: upstairs (audio: running tap)", "  [0.86] clothes_airer: folded, by door, empty", "  [0.85] curtains: drawn, 0.4 m from heater", "  [0.84] smoke_alarm: hallway, LED green"],
"w09-0274": ["  wristband_ocr: \"OWUSU, Kofi - ALLERGIES: NONE KNOWN\"", "  glucose_meter_ocr: \"7.8 mmol/L 13:50\"", "  swallow_plan: none in place", "  tray: tea, half drunk", "  patient_posture: sitting in chair, alert"],
"w09-0279": ["  corridor: {lighting: night mode 30 %, floor: dry}", "  door_705: {state: closed}", "  door_709: {state: closed, DND: true}", "  audio_707: \"snoring, steady\"", "  night_manager: {pager: available}"],
"w09-0280": ["  [0.88] toaster: 1.2 m from sink, dry", "  [0.87] window: open", "  [0.86] dog: none", "  [0.85] phone_on_cable: on worktop edge, screen lit", "  [0.84] floor: small splash by sink"],
"w09-p114": ["  room_lights: on", "  guest_posture: folding clothes into small case", "  towel: on bed, dry", "  taxi_note_ocr: \"Taxi 11:30\""],
"w09-p116": ["  [0.89] colander: in sink", "  [0.88] wooden_spoon: on spoon rest", "  [0.87] table: set for three", "  [0.86] floor: dry"],
"w09-p118": [" - corridor: dry, lights 100 %", " - cctv: dome above lift", " - trolley: brakes on, towels and bin bag", " - guest_parent posture: holding child's hand, looking at signs"],
"w09-p119": ["  [0.87] gravel: in bowl, clean", "  [0.86] table: towel laid out, jug on it", "  [0.85] fish_state: swimming normally", "  [0.84] room: lights on, TV off"],
"w09-0305": ["  [0.87] shed_door: open, sunny", "  [0.86] lawn: long grass", "  [0.85] leaf_pile: 0.5 m high, damp", "  [0.84] hedgehog_house: empty, by fence", "  [0.83] fuel_can: capped"],
"w09-0306": ["  gate: {state: closed, latch: keypad}", "  other_children: {count: 5, activity: \"at story mat\"}", "  coat_peg_ocr: \"RUBY\" (red coat, bag)", "  time_on_register: \"16:40 - expected collection 16:45\""],
"w09-0307": [" det fume cupboard: OFF", " det other students: 2, at door", " det chemical store: open, key in lock", " det clock OCR \"09:40\""],
"w09-0308": ["  room_915_lights: off (door log: last exit 21:10)", "  corridor: {floor: dry, lights: on}", "  guest_posture: standing, holding passport open at photo page", "  face_match_passport: 0.95", "  front_desk_note_ocr: \"Re-issue cards on ID match\""],
"w09-0309": ["  [0.89] crate: door open, blanket inside", "  [0.88] window: closed", "  [0.87] sofa: throw over back", "  [0.86] shelf: 1.5 m, empty", "  [0.85] rug: chewed corner"],
"w09-0310": ["  monitor: {hr: 92, spo2: 97}", "  wound_dressing: {state: dry, intact}", "  curtain: open, corridor visible", "  relative_posture: standing at bed end, phone raised", "  sign_ocr: \"No photography of patients without consent\""],
"w09-0313": ["tools: {hooks: [spade, fork, rake]}", "floor: {state: dry, concrete}", "light: {state: on}", "person_1_footwear: {type: boots}"],
"w09-0314": ["[18:40:14] det fire blanket on wall by door", "[18:40:14] det plates x3 on table", "[18:40:15] det adult none; TV audible next room", "[18:40:15] det fryer lid open"],
"w09-0315": ["- corridor: dry, lights 100 %", "- trolley: towels and toiletries", "- glasses_case_OCR: \"Rm 503 - found table 8 - 08:10\"", "- guest_A posture: hand out, smiling"],
"w09-0317": [" - tank_lid: mesh, closed", " - axolotls: gills fanned, resting on bottom", " - clock OCR \"12:45\"", " - teacher: est 30-40 y, at desk eating lunch"],
"w09-0318": ["  [0.87] tv: on, afternoon quiz", "  [0.86] blanket: over grandmother's knees", "  [0.85] tea_cup: cold, on side table", "  [0.84] parent: none (car heard leaving 14:50)"],
"w09-0319": [" det car battery on bench, vent caps in place", " det charger clamps: red on +, black on -", " det floor dry; no fuel stored near", " det light on"],
"w09-p125": ["  corridor: {lighting: night mode, floor: dry}", "  room_1008_booking_tablet_ocr: \"1008 - 1 guest - checked in 19:40\"", "  guest_1006_posture: in dressing gown, worried", "  cctv: dome at lift"],
"w09-p128": [" - lips: dry, cracked (conf 0.74)", " - spit_bowl: kidney dish on locker", " - iv_fluids: running, OCR \"Hartmann's 83 ml/h\"", " - call_bell: in reach"],
"w09-p129": ["  [0.89] window: sunny, curtains open", "  [0.88] dog: asleep at his feet", "  [0.87] tissue_box: on table", "  [0.86] chilli_oil_jar: dropper in lid"],
"w09-0340": ["  [0.88] drainer: plates, glasses", "  [0.87] window: open, garden", "  [0.86] rubber gloves: on sink edge", "  [0.85] floor: dry", "  [0.84] radio: on low"],
"w09-0341": ["[12:12:52] det other children x4 in sandpit 8 m away", "[12:12:53] det shed door open 15 m", "[12:12:53] det water_tray on grass, stable", "[12:12:53] det sun cream on bench"],
"w09-0342": [" det lab fridge door OCR \"BIOLOGICAL - Category 1 organisms\"", " det bench: microscopes covered", " det staff room: corridor, fridge full (teacher statement)", " det clock OCR \"15:20\"", " det students: none"],
"w09-0344": ["  [0.87] shed_door: open, sunny", "  [0.86] tools on bench: hammer, screwdriver", "  [0.85] mother cat: in garden 6 m", "  [0.84] child_1 posture: hand on lid, laughing", "  [0.83] floor: dry, sawdust"],
"w09-0345": ["  room_lights: on", "  guest_posture: sitting in armchair, glass of water in hand", "  bathroom_floor: dry", "  washbag_other_contents: toothbrush, razor (capped)"],
"w09-0346": ["  [0.89] dog_bed: soft, by window", "  [0.88] water_bowl: full", "  [0.87] room_temp_ocr: \"23 C\"", "  [0.86] greyhound posture: lying down, ears back", "  [0.85] window: closed"],
"w09-0347": [" - kitchen floor: dry, tiled", " - lasagne dish: ceramic, in oven middle shelf", " - hallway: toy basket, shoes", " - hob: all OFF, back rings clear"],
"w09-0348": ["  patient_posture: sitting up, reading", "  cannula: left hand, site clean (OCR VIP chart \"score 0\")", "  pump: infusion pump, idle", "  bin_sharps: on trolley"],
"w09-0349": ["[09:10:06] det luggage: grey case, black holdall, umbrella", "[09:10:07] det room_209 door closed, guest in breakfast room (per tablet)", "[09:10:07] det corridor dry, lights on", "[09:10:07] det trolley_luggage brake on"],
"w09-0350": ["  [0.89] windows: closed", "  [0.88] fume cupboard: OFF, empty", "  [0.87] chemical store: locked", "  [0.86] clock: OCR \"16:00\"", "  [0.85] gas smell sensor: normal"],
}
rows = list(csv.DictReader(open(P, encoding="utf-8")))
cols = list(rows[0].keys())
done = set()
for r in rows:
    key = r["pair"] if r["pair"] in X else r["id"]
    if key not in X: continue
    scene, sep, rest = r["text"].partition("\nTASK:")
    assert sep, r["id"]
    r["text"] = scene.rstrip() + "\n" + "\n".join(X[key]) + "\nTASK:" + rest
    done.add(key)
assert done == set(X), set(X) - done
with open(P, "w", newline="", encoding="utf-8") as f:
    w = csv.DictWriter(f, fieldnames=cols); w.writeheader(); w.writerows(rows)
print("amended", len(done), "keys")
