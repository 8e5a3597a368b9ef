<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="de_DE">
<context>
    <name>Engine</name>
    <message>
        <source>no correspondences</source>
        <translation>keine Korrespondenzen</translation>
    </message>
    <message>
        <source>only %1 % of pixels matched</source>
        <translation>nur %1 % der Pixel zugeordnet</translation>
    </message>
    <message>
        <source>ill-conditioned (geometry and texture too poor)</source>
        <translation>schlecht konditioniert (zu wenig Geometrie und Textur)</translation>
    </message>
    <message>
        <source>pose jumped implausibly far</source>
        <translation>die Pose sprang unplausibel weit</translation>
    </message>
    <message>
        <source>point-to-surface error %1 cm, %2x the scan&apos;s usual %3 cm</source>
        <translation>Punkt-zu-Fläche-Fehler %1 cm, %2-mal so groß wie die für diesen Scan üblichen %3 cm</translation>
    </message>
    <message>
        <source>radiance residual %1, %2x the scan&apos;s usual %3</source>
        <translation>Radianz-Residuum %1, %2-mal so groß wie das für diesen Scan übliche %3</translation>
    </message>
    <message>
        <source>only %1 % of the matched pixels fit the pose</source>
        <translation>nur %1 % der zugeordneten Pixel passen zur Pose</translation>
    </message>
    <message>
        <source>the exposure the pose implies is %1x the sensor&apos;s reported exposure (relative to the scan so far)</source>
        <translation>die aus der Pose folgende Belichtung ist das %1-Fache der vom Sensor gemeldeten (relativ zum bisherigen Scan)</translation>
    </message>
    <message>
        <source>waiting for a frame to anchor the model: %1 % of its pixels have depth, %2 % needed</source>
        <translation>warte auf ein Bild, das das Modell verankert: %1 % seiner Pixel haben Tiefe, %2 % sind nötig</translation>
    </message>
    <message>
        <source>confirming the pose after a loss (%1 of %2 frames)</source>
        <translation>bestätige die Pose nach einem Verlust (%1 von %2 Bildern)</translation>
    </message>
    <message>
        <source>%1 % of the image is saturated even at the shortest exposure (%2 ms): the brightest parts add nothing to the top of the curve</source>
        <translation>%1 % des Bildes sind selbst bei der kürzesten Belichtung (%2 ms) gesättigt: die hellsten Teile tragen nichts zum oberen Ende der Kurve bei</translation>
    </message>
    <message>
        <source>the scene spans %1 stops: steps widened to %2 stops to stay within %3 exposures</source>
        <translation>die Szene umfasst %1 Blendenstufen: Schritte auf %2 Blendenstufen verbreitert, um bei höchstens %3 Belichtungen zu bleiben</translation>
    </message>
    <message>
        <source>the planned sweep covers %1 % of the levels of channel %2 (widest gap: levels %3 to %4): the curve is interpolated there</source>
        <translation>die geplante Belichtungsreihe deckt %1 % der Stufen von Kanal %2 ab (größte Lücke: Stufen %3 bis %4): dort wird die Kurve interpoliert</translation>
    </message>
    <message>
        <source>the planned sweep covers %1 % of the levels of channel %2: the curve is interpolated there</source>
        <translation>die geplante Belichtungsreihe deckt %1 % der Stufen von Kanal %2 ab: in den Lücken wird die Kurve interpoliert</translation>
    </message>
    <message>
        <source>%1: auto exposure is on (as the camera reports it); the camera would choose its own exposures and the sweep&apos;s would not be the ones recorded. Lock auto exposure and try again.</source>
        <translation>%1: die automatische Belichtung ist eingeschaltet (laut Kamera); die Kamera würde ihre eigenen Belichtungen wählen, und die aufgezeichneten wären nicht die der Belichtungsreihe. Automatische Belichtung sperren und erneut versuchen.</translation>
    </message>
    <message>
        <source>%1: auto white balance is on (as the camera reports it); it would change the colour gains between exposures. Lock white balance and try again.</source>
        <translation>%1: der automatische Weißabgleich ist eingeschaltet (laut Kamera); er würde die Farbverstärkungen zwischen den Belichtungen ändern. Weißabgleich sperren und erneut versuchen.</translation>
    </message>
    <message>
        <source>%1: the images did not brighten when the exposure was set 2 stops longer (mean level %2 at %3 ms, %4 at %5 ms); the camera is not taking the exposure it is given (automatic exposure still acting?). Lock auto exposure and try again.</source>
        <translation>%1: die Bilder wurden nicht heller, als die Belichtung um 2 Blendenstufen verlängert wurde (mittlere Stufe %2 bei %3 ms, %4 bei %5 ms); die Kamera übernimmt die vorgegebene Belichtung nicht (wirkt die automatische Belichtung noch?). Automatische Belichtung sperren und erneut versuchen.</translation>
    </message>
    <message>
        <source>%1: even at the shortest exposure (%2 ms) %3 % of the image is saturated. Dim the lights, point the camera at a darker scene or lower its gain, then plan again.</source>
        <translation>%1: selbst bei der kürzesten Belichtung (%2 ms) sind %3 % des Bildes gesättigt. Licht dämpfen, die Kamera auf eine dunklere Szene richten oder ihre Verstärkung senken, dann erneut planen.</translation>
    </message>
    <message>
        <source>%1: even at the longest exposure (%2 ms) %3 % of the image is black. Light the scene, or point the camera at a brighter one, then plan again.</source>
        <translation>%1: selbst bei der längsten Belichtung (%2 ms) sind %3 % des Bildes schwarz. Die Szene beleuchten oder die Kamera auf eine hellere richten, dann erneut planen.</translation>
    </message>
    <message>
        <source>%1: the camera&apos;s exposures (%2 ms to %3 ms) give fewer than 3 distinct exposures; calibration needs 3 or more</source>
        <translation>%1: die Belichtungen der Kamera (%2 ms bis %3 ms) ergeben weniger als 3 verschiedene Belichtungen; die Kalibrierung braucht 3 oder mehr</translation>
    </message>
    <message>
        <source>%1: the planned sweep covers only %2 % of the levels of channel %3 (widest gap: levels %4 to %5). Point the camera at a scene with dark and bright parts and many shades between (not a wall or a grey card), then plan again.</source>
        <translation>%1: die geplante Belichtungsreihe deckt nur %2 % der Stufen von Kanal %3 ab (größte Lücke: Stufen %4 bis %5). Die Kamera auf eine Szene mit dunklen und hellen Teilen und vielen Abstufungen dazwischen richten (keine Wand, keine Graukarte), dann erneut planen.</translation>
    </message>
    <message>
        <source>%1: the planned sweep covers only %2 % of the levels of channel %3. Point the camera at a scene with dark and bright parts and many shades between (not a wall or a grey card), then plan again.</source>
        <translation>%1: die geplante Belichtungsreihe deckt nur %2 % der Stufen von Kanal %3 ab. Die Kamera auf eine Szene mit dunklen und hellen Teilen und vielen Abstufungen dazwischen richten (keine Wand, keine Graukarte), dann erneut planen.</translation>
    </message>
    <message>
        <source>planning cancelled</source>
        <translation>Planung abgebrochen</translation>
    </message>
    <message>
        <source>the image changed between repeats (%1 % of image regions changed brightness order): the camera or the scene moved</source>
        <translation>das Bild änderte sich zwischen den Wiederholungen (in %1 % der Bildbereiche änderte sich die Helligkeitsreihenfolge): Kamera oder Szene haben sich bewegt</translation>
    </message>
    <message>
        <source>the brightness changed by %1 % between repeats: flickering light</source>
        <translation>die Helligkeit änderte sich zwischen den Wiederholungen um %1 %: flackerndes Licht</translation>
    </message>
    <message>
        <source>the image no longer matches the exposure before (%1 % of image regions changed brightness order): the camera or the scene moved</source>
        <translation>das Bild passt nicht mehr zur vorigen Belichtung (in %1 % der Bildbereiche änderte sich die Helligkeitsreihenfolge): Kamera oder Szene haben sich bewegt</translation>
    </message>
    <message>
        <source>re-capturing %1 ms: %2</source>
        <translation>nehme %1 ms erneut auf: %2</translation>
    </message>
    <message>
        <source>At %1 ms (step %2 of %3) %4, %5 times in a row. %6 The %7 steps captured so far are kept in %8.</source>
        <translation>Bei %1 ms (Schritt %2 von %3): %4, %5-mal in Folge. %6 Die %7 bisher aufgenommenen Schritte bleiben in %8 erhalten.</translation>
    </message>
    <message>
        <source>Switch off fluorescent or dimmed LED lights (or use daylight), then resume.</source>
        <translation>Leuchtstofflampen oder gedimmte LED-Lampen ausschalten (oder Tageslicht nutzen), dann fortsetzen.</translation>
    </message>
    <message>
        <source>The camera was moved: put it back exactly where it was, or start a new sweep.</source>
        <translation>Die Kamera wurde bewegt: sie genau an ihren Platz zurückstellen oder eine neue Belichtungsreihe beginnen.</translation>
    </message>
    <message>
        <source>Put the camera on a tripod or a table and keep the scene still, then resume.</source>
        <translation>Die Kamera auf ein Stativ oder einen Tisch stellen und die Szene ruhig halten, dann fortsetzen.</translation>
    </message>
    <message>
        <source>%1 of %2 exposures disagree with the merge by more than %3 stops (worst %4 stops at %5 ms): the exposure times do not match the images, or the scene changed</source>
        <translation>%1 von %2 Belichtungen weichen um mehr als %3 Blendenstufen von der Zusammenführung ab (am stärksten %4 Blendenstufen bei %5 ms): die Belichtungszeiten passen nicht zu den Bildern, oder die Szene hat sich geändert</translation>
    </message>
    <message>
        <source>%1 of %2 exposures disagree with the merge by more than %3 stops (worst %4 stops at %5 ms); good is below %6 stops</source>
        <translation>%1 von %2 Belichtungen weichen um mehr als %3 Blendenstufen von der Zusammenführung ab (am stärksten %4 Blendenstufen bei %5 ms); gut ist unter %6 Blendenstufen</translation>
    </message>
    <message>
        <source>too few well-exposed pixels at %1 ms to check the fit on a held-back exposure</source>
        <translation>zu wenige gut belichtete Pixel bei %1 ms, um die Anpassung an einer zurückgehaltenen Belichtung zu prüfen</translation>
    </message>
    <message>
        <source>the %1 ms exposure, held back, is predicted from the others only within %2 stops (limit %3 stops): the response does not hold between exposures</source>
        <translation>die zurückgehaltene Belichtung von %1 ms wird aus den anderen nur auf %2 Blendenstufen genau vorhergesagt (Grenze %3 Blendenstufen): die Antwortkurve gilt nicht zwischen den Belichtungen</translation>
    </message>
    <message>
        <source>the %1 ms exposure, held back, is predicted within %2 stops (good below %3 stops)</source>
        <translation>die zurückgehaltene Belichtung von %1 ms wird auf %2 Blendenstufen genau vorhergesagt (gut unter %3 Blendenstufen)</translation>
    </message>
    <message>
        <source>the fit without the %1 ms exposure failed: %2</source>
        <translation>die Anpassung ohne die Belichtung von %1 ms schlug fehl: %2</translation>
    </message>
    <message>
        <source>%1 % of the %2 levels are covered (levels %3 to %4 not seen): the curve is interpolated there; a scene with more distinct brightnesses covers them</source>
        <translation>%1 % der Stufen von %2 sind abgedeckt (Stufen %3 bis %4 nicht gesehen): dort wird die Kurve interpoliert; eine Szene mit mehr verschiedenen Helligkeiten deckt sie ab</translation>
    </message>
    <message>
        <source>exposures up to %1 stops apart; steps of a stop or less pin the curve down near saturation</source>
        <translation>Belichtungen bis zu %1 Blendenstufen auseinander; Schritte von einer Blendenstufe oder weniger legen die Kurve nahe der Sättigung fest</translation>
    </message>
    <message>
        <source>the noise level function does not fit the measured noise (rms relative misfit %1, limit %2): it is not saved</source>
        <translation>die Rauschfunktion passt nicht zum gemessenen Rauschen (relative RMS-Abweichung %1, Grenze %2): sie wird nicht gespeichert</translation>
    </message>
    <message>
        <source>device &apos;%1&apos; cannot register depth to colour: depth is used as delivered</source>
        <translation>Gerät „%1“ kann die Tiefe nicht auf die Farbe registrieren: die Tiefe wird wie geliefert verwendet</translation>
    </message>
    <message>
        <source>%1 is missing: the built-in Asus Xtion profile is assumed</source>
        <translation>%1 fehlt: das eingebaute Asus-Xtion-Profil wird angenommen</translation>
    </message>
    <message>
        <source>%1 is missing: every frame is of unknown exposure</source>
        <translation>%1 fehlt: die Belichtung jedes Bildes ist unbekannt</translation>
    </message>
    <message>
        <source>no profile for device &apos;%1&apos; (serial %2) in %3: using the built-in Asus Xtion profile. Its response and intrinsics are not this device&apos;s own; calibrate it with hdrfusion-calibration-wizard (or hdrfusion capture-sweep, then hdrfusion calibrate --save-profile), which stores its profile as %4</source>
        <translation>kein Profil für Gerät „%1“ (Seriennummer %2) in %3: das eingebaute Asus-Xtion-Profil wird verwendet. Seine Antwortkurve und Intrinsik sind nicht die dieses Geräts; kalibrieren Sie es mit hdrfusion-calibration-wizard (oder hdrfusion capture-sweep, dann hdrfusion calibrate --save-profile), das sein Profil als %4 speichert</translation>
    </message>
    <message>
        <source>no profile for device &apos;%1&apos; in %2: using the built-in Asus Xtion profile. Its response and intrinsics are not this device&apos;s own; calibrate it with hdrfusion-calibration-wizard (or hdrfusion capture-sweep, then hdrfusion calibrate --save-profile), which stores its profile as %3</source>
        <translation>kein Profil für Gerät „%1“ in %2: das eingebaute Asus-Xtion-Profil wird verwendet. Seine Antwortkurve und Intrinsik sind nicht die dieses Geräts; kalibrieren Sie es mit hdrfusion-calibration-wizard (oder hdrfusion capture-sweep, dann hdrfusion calibrate --save-profile), das sein Profil als %3 speichert</translation>
    </message>
    <message>
        <source>the profile gives no exposure unit for this device (&apos;hdrfusion.device.exposure_ms_per_unit&apos;): frames are recorded as of unknown exposure and the engine estimates exposure ratios itself</source>
        <translation>das Profil nennt keine Belichtungseinheit für dieses Gerät („hdrfusion.device.exposure_ms_per_unit“): Bilder werden mit unbekannter Belichtung aufgezeichnet, und die Engine schätzt die Belichtungsverhältnisse selbst</translation>
    </message>
    <message>
        <source>%1: the &apos;synthetic&apos; block is not this project&apos;s (it holds other keys); ignored</source>
        <translation>%1: der Block „synthetic“ stammt nicht von diesem Projekt (er enthält andere Schlüssel); ignoriert</translation>
    </message>
    <message>
        <source>%1: the &apos;synthetic&apos; block is not this project&apos;s (it holds no object); ignored</source>
        <translation>%1: der Block „synthetic“ stammt nicht von diesem Projekt (er enthält kein Objekt); ignoriert</translation>
    </message>
    <message>
        <source>%1 has no &apos;response&apos; calibration: the sRGB curve is assumed, so the HDR radiance is only as good as that guess</source>
        <translation>%1 enthält keine „response“-Kalibrierung: die sRGB-Kurve wird angenommen, die HDR-Radianz ist also nur so gut wie diese Annahme</translation>
    </message>
    <message>
        <source>the scan has no keyframes: the texture holds the volume&apos;s radiance only (as sharp as the voxels)</source>
        <translation>der Scan hat keine Schlüsselbilder: die Textur enthält nur die Radianz des Volumens (so scharf wie die Voxel)</translation>
    </message>
    <message>
        <source>the pose moved %1 m in %2 ms since the last accepted one (%3 m/s, more than %4 m/s)</source>
        <translation>die Pose hat sich seit der letzten angenommenen um %1 m in %2 ms bewegt (%3 m/s, mehr als %4 m/s)</translation>
    </message>
    <message>
        <source>the pose departs from the predicted motion by %1 cm and %2 degrees, %3x what a hand-held camera does</source>
        <translation>die Pose weicht um %1 cm und %2 Grad von der vorhergesagten Bewegung ab, das %3-Fache dessen, was eine Kamera in der Hand tut</translation>
    </message>
    <message>
        <source>recovering, and only %1 % of the matched pixels have usable colour (the rest clipped or dark): too little to confirm the pose</source>
        <translation>in der Wiederherstellung, und nur %1 % der zugeordneten Pixel haben brauchbare Farbe (der Rest übersteuert oder dunkel): zu wenig, um die Pose zu bestätigen</translation>
    </message>
    <message>
        <source>tracker.levels %1 lowered to %2 for %3x%4 frames (a pyramid level under %5x%6 pixels misleads the tracker)</source>
        <translation>tracker.levels von %1 auf %2 gesenkt für Bilder von %3x%4 (eine Pyramidenstufe unter %5x%6 Pixeln führt den Tracker in die Irre)</translation>
    </message>
    <message>
        <source>CUDA requested but not usable (%1); running on the CPU</source>
        <translation>CUDA verlangt, aber nicht nutzbar (%1); läuft auf der CPU</translation>
    </message>
    <message>
        <source>removed %1 recovery files of earlier unfinished scans (%2 MiB) from %3: older than %4 days, or beyond the newest %5 and %6 GiB</source>
        <translation>%1 Wiederherstellungsdateien früherer unvollendeter Scans (%2 MiB) aus %3 entfernt: älter als %4 Tage oder jenseits der neuesten %5 und %6 GiB</translation>
    </message>
</context>
<context>
    <name>QObject</name>
    <message>
        <source>on or off</source>
        <translation>ein oder aus</translation>
    </message>
    <message>
        <source>one of %1</source>
        <translation>eines von %1</translation>
    </message>
    <message>
        <source>1 to %1 whole numbers, each %2 .. %3</source>
        <translation>1 bis %1 ganze Zahlen, jede %2 .. %3</translation>
    </message>
    <message>
        <source>Engine</source>
        <translation>Engine</translation>
    </message>
    <message>
        <source>Volume</source>
        <translation>Volumen</translation>
    </message>
    <message>
        <source>Tracking</source>
        <translation>Tracking</translation>
    </message>
    <message>
        <source>Exposure compensation</source>
        <translation>Belichtungsausgleich</translation>
    </message>
    <message>
        <source>Normalized radiance</source>
        <translation>Normalisierte Radianz</translation>
    </message>
    <message>
        <source>Depth</source>
        <translation>Tiefe</translation>
    </message>
    <message>
        <source>Relocalisation</source>
        <translation>Relokalisierung</translation>
    </message>
    <message>
        <source>radiance %1 %2 %3</source>
        <translation>Radianz %1 %2 %3</translation>
    </message>
    <message>
        <source>frames</source>
        <translation>Bilder</translation>
    </message>
    <message>
        <source>voxels</source>
        <translation>Voxel</translation>
    </message>
</context>
<context>
    <name>Report</name>
    <message>
        <source>Camera calibration</source>
        <translation>Kamerakalibrierung</translation>
    </message>
    <message>
        <source>Serial</source>
        <translation>Seriennummer</translation>
    </message>
    <message>
        <source>Date</source>
        <translation>Datum</translation>
    </message>
    <message>
        <source>Sweep</source>
        <translation>Belichtungsreihe</translation>
    </message>
    <message>
        <source>frames</source>
        <translation>Bilder</translation>
    </message>
    <message>
        <source>exposures from</source>
        <translation>Belichtungen von</translation>
    </message>
    <message>
        <source>to</source>
        <translation>bis</translation>
    </message>
    <message>
        <source>Method</source>
        <translation>Verfahren</translation>
    </message>
    <message>
        <source>Verdict</source>
        <translation>Urteil</translation>
    </message>
    <message>
        <source>every check within its limit</source>
        <translation>jede Prüfung innerhalb ihrer Grenze</translation>
    </message>
    <message>
        <source>Held back</source>
        <translation>Zurückgehalten</translation>
    </message>
    <message>
        <source>predicted from the others within</source>
        <translation>aus den anderen vorhergesagt auf</translation>
    </message>
    <message>
        <source>stops</source>
        <translation>Blendenstufen</translation>
    </message>
    <message>
        <source>Levels covered</source>
        <translation>Abgedeckte Stufen</translation>
    </message>
    <message>
        <source>channel</source>
        <translation>Kanal</translation>
    </message>
    <message>
        <source>rms log residual</source>
        <translation>RMS-Log-Residuum</translation>
    </message>
    <message>
        <source>noise misfit</source>
        <translation>Rauschabweichung</translation>
    </message>
    <message>
        <source>not fitted</source>
        <translation>nicht angepasst</translation>
    </message>
    <message>
        <source>The noise level function is saved with the response.</source>
        <translation>Die Rauschfunktion wird mit der Antwortkurve gespeichert.</translation>
    </message>
    <message>
        <source>The noise level function is not saved (see above); the engine uses a generic one derived from the response.</source>
        <translation>Die Rauschfunktion wird nicht gespeichert (siehe oben); die Engine verwendet eine allgemeine, aus der Antwortkurve abgeleitete.</translation>
    </message>
    <message>
        <source>Exposures</source>
        <translation>Belichtungen</translation>
    </message>
    <message>
        <source>exposure (ms)</source>
        <translation>Belichtung (ms)</translation>
    </message>
    <message>
        <source>median |deviation| (stops)</source>
        <translation>Median |Abweichung| (Blendenstufen)</translation>
    </message>
    <message>
        <source>samples</source>
        <translation>Stichproben</translation>
    </message>
    <message>
        <source>Plots</source>
        <translation>Diagramme</translation>
    </message>
    <message>
        <source>Profile</source>
        <translation>Profil</translation>
    </message>
</context>
<context>
    <name>Settings</name>
    <message>
        <source>Run on</source>
        <translation>Ausführen auf</translation>
    </message>
    <message>
        <source>Where the engine runs (cuda: the GPU where one is usable)</source>
        <translation>Wo die Engine läuft (cuda: auf der GPU, wo eine nutzbar ist)</translation>
    </message>
    <message>
        <source>Keep cuda where a GPU answers; cpu to compare with the reference or when the GPU is busy</source>
        <translation>cuda beibehalten, wo eine GPU antwortet; cpu zum Vergleich mit der Referenz oder wenn die GPU ausgelastet ist</translation>
    </message>
    <message>
        <source>Pixel confidence</source>
        <translation>Pixelkonfidenz</translation>
    </message>
    <message>
        <source>Pixel confidence p0..p3 used for tracking and fusion (p1: square root)</source>
        <translation>Pixelkonfidenz p0..p3 für Tracking und Fusion (p1: Quadratwurzel)</translation>
    </message>
    <message>
        <source>Keep p1; p0 trusts every pixel alike, p2 and p3 trust mid-tones more</source>
        <translation>p1 beibehalten; p0 vertraut allen Pixeln gleich, p2 und p3 vertrauen Mitteltönen mehr</translation>
    </message>
    <message>
        <source>Voxel size</source>
        <translation>Voxelgröße</translation>
    </message>
    <message>
        <source>Voxel side; the volume has no fixed extent, its memory follows the surface seen</source>
        <translation>Kantenlänge eines Voxels; das Volumen hat keine feste Ausdehnung, sein Speicher folgt der gesehenen Oberfläche</translation>
    </message>
    <message>
        <source>Smaller for small objects and sharper colour (memory grows about 4x per halving); larger for big rooms</source>
        <translation>Kleiner für kleine Objekte und schärfere Farbe (der Speicher wächst etwa 4-fach je Halbierung); größer für große Räume</translation>
    </message>
    <message>
        <source>Voxel storage</source>
        <translation>Voxelspeicherung</translation>
    </message>
    <message>
        <source>Voxel storage: compact (12 B), no-nr (24 B) or full (28 B)</source>
        <translation>Voxelspeicherung: compact (12 B), no-nr (24 B) oder full (28 B)</translation>
    </message>
    <message>
        <source>compact for scanning; full only to inspect the normalized radiance stored in the model</source>
        <translation>compact zum Scannen; full nur, um die im Modell gespeicherte normalisierte Radianz zu untersuchen</translation>
    </message>
    <message>
        <source>Surface band</source>
        <translation>Oberflächenband</translation>
    </message>
    <message>
        <source>TSDF truncation distance</source>
        <translation>TSDF-Abschneidedistanz</translation>
    </message>
    <message>
        <source>Wider for noisy depth, narrower to keep thin objects apart</source>
        <translation>Breiter für verrauschte Tiefe, schmaler, um dünne Objekte getrennt zu halten</translation>
    </message>
    <message>
        <source>Geometry memory</source>
        <translation>Geometriegedächtnis</translation>
    </message>
    <message>
        <source>Cap of the TSDF weight (running-mean window)</source>
        <translation>Obergrenze des TSDF-Gewichts (Fenster des gleitenden Mittels)</translation>
    </message>
    <message>
        <source>Lower so that moving objects fade from the model sooner</source>
        <translation>Niedriger, damit bewegte Objekte schneller aus dem Modell verschwinden</translation>
    </message>
    <message>
        <source>Colour memory</source>
        <translation>Farbgedächtnis</translation>
    </message>
    <message>
        <source>Cap of the radiance weight</source>
        <translation>Obergrenze des Radianzgewichts</translation>
    </message>
    <message>
        <source>Lower so that colour follows changing light sooner</source>
        <translation>Niedriger, damit die Farbe wechselndem Licht schneller folgt</translation>
    </message>
    <message>
        <source>Colour confidence threshold</source>
        <translation>Schwelle der Farbkonfidenz</translation>
    </message>
    <message>
        <source>Radiance is fused only where the largest channel PCF exceeds this</source>
        <translation>Radianz wird nur fusioniert, wo die PCF des größten Kanals diesen Wert übersteigt</translation>
    </message>
    <message>
        <source>Raise to keep dark or clipped pixels out of the colour</source>
        <translation>Erhöhen, um dunkle oder übersteuerte Pixel aus der Farbe herauszuhalten</translation>
    </message>
    <message>
        <source>Colour viewing angle limit</source>
        <translation>Grenze des Blickwinkels für Farbe</translation>
    </message>
    <message>
        <source>Radiance is fused only where the angle between normal and view ray is below this</source>
        <translation>Radianz wird nur fusioniert, wo der Winkel zwischen Normale und Sehstrahl darunter liegt</translation>
    </message>
    <message>
        <source>Lower to take colour only from views that face the surface</source>
        <translation>Niedriger, um Farbe nur aus Ansichten zu nehmen, die der Oberfläche zugewandt sind</translation>
    </message>
    <message>
        <source>Model memory limit</source>
        <translation>Speichergrenze des Modells</translation>
    </message>
    <message>
        <source>Voxel memory the whole model may use</source>
        <translation>Voxelspeicher, den das ganze Modell belegen darf</translation>
    </message>
    <message>
        <source>Raise for large rooms when the volume reports it is full</source>
        <translation>Erhöhen für große Räume, wenn das Volumen meldet, dass es voll ist</translation>
    </message>
    <message>
        <source>GPU memory limit</source>
        <translation>GPU-Speichergrenze</translation>
    </message>
    <message>
        <source>GPU only: voxel memory on the GPU; beyond it, bricks out of view move to host memory and back when seen again (0: no GPU budget; 4 MiB at least)</source>
        <translation>Nur GPU: Voxelspeicher auf der GPU; darüber hinaus wandern Bricks außer Sicht in den Hauptspeicher und zurück, wenn sie wieder gesehen werden (0: keine GPU-Grenze; mindestens 4 MiB)</translation>
    </message>
    <message>
        <source>Set on a GPU with little memory; 0 lets the model use the GPU alone</source>
        <translation>Auf einer GPU mit wenig Speicher setzen; 0 lässt das Modell allein auf der GPU</translation>
    </message>
    <message>
        <source>Nearest model distance</source>
        <translation>Nächste Modellentfernung</translation>
    </message>
    <message>
        <source>Ray casting starts this far from the camera</source>
        <translation>Das Raycasting beginnt in dieser Entfernung von der Kamera</translation>
    </message>
    <message>
        <source>Lower when scanning objects closer than it</source>
        <translation>Niedriger, wenn Objekte näher als dieser Wert gescannt werden</translation>
    </message>
    <message>
        <source>Farthest model distance</source>
        <translation>Fernste Modellentfernung</translation>
    </message>
    <message>
        <source>Ray casting gives up this far from the camera</source>
        <translation>Das Raycasting gibt in dieser Entfernung von der Kamera auf</translation>
    </message>
    <message>
        <source>Raise when tracking should use surfaces farther away (large halls)</source>
        <translation>Erhöhen, wenn das Tracking weiter entfernte Flächen nutzen soll (große Hallen)</translation>
    </message>
    <message>
        <source>Tracking method</source>
        <translation>Tracking-Verfahren</translation>
    </message>
    <message>
        <source>nr+icp, nr (normalized radiance), icp, or intensity (the brightness-constancy baseline)</source>
        <translation>nr+icp, nr (normalisierte Radianz), icp oder intensity (die Vergleichsbasis mit Helligkeitskonstanz)</translation>
    </message>
    <message>
        <source>Keep nr+icp; icp alone for scenes without texture, intensity only to compare</source>
        <translation>nr+icp beibehalten; icp allein für Szenen ohne Textur, intensity nur zum Vergleich</translation>
    </message>
    <message>
        <source>Track against the model</source>
        <translation>Gegen das Modell tracken</translation>
    </message>
    <message>
        <source>Track against the model (false: against the previous frame)</source>
        <translation>Gegen das Modell tracken (false: gegen das vorige Bild)</translation>
    </message>
    <message>
        <source>Turn off only to compare with frame-to-frame tracking</source>
        <translation>Nur ausschalten, um mit Bild-zu-Bild-Tracking zu vergleichen</translation>
    </message>
    <message>
        <source>Image pyramid levels</source>
        <translation>Stufen der Bildpyramide</translation>
    </message>
    <message>
        <source>Pyramid levels, each half the size</source>
        <translation>Pyramidenstufen, jede halb so groß</translation>
    </message>
    <message>
        <source>More for fast motion, fewer for small images</source>
        <translation>Mehr für schnelle Bewegung, weniger für kleine Bilder</translation>
    </message>
    <message>
        <source>Iterations per level</source>
        <translation>Iterationen je Stufe</translation>
    </message>
    <message>
        <source>Gauss-Newton iterations per level, coarsest first</source>
        <translation>Gauß-Newton-Iterationen je Stufe, die gröbste zuerst</translation>
    </message>
    <message>
        <source>More when tracking is lost on fast motion; fewer for speed</source>
        <translation>Mehr, wenn das Tracking bei schneller Bewegung verloren geht; weniger für Geschwindigkeit</translation>
    </message>
    <message>
        <source>Depth residual scale</source>
        <translation>Skala des Tiefenresiduums</translation>
    </message>
    <message>
        <source>Expected scale of the point-to-plane residual</source>
        <translation>Erwartete Größe des Punkt-zu-Ebene-Residuums</translation>
    </message>
    <message>
        <source>Raise for noisy depth sensors</source>
        <translation>Erhöhen für verrauschte Tiefensensoren</translation>
    </message>
    <message>
        <source>Colour residual scale</source>
        <translation>Skala des Farbresiduums</translation>
    </message>
    <message>
        <source>Expected scale of the normalized-radiance residual</source>
        <translation>Erwartete Größe des Residuums der normalisierten Radianz</translation>
    </message>
    <message>
        <source>Raise for noisy colour</source>
        <translation>Erhöhen für verrauschte Farbe</translation>
    </message>
    <message>
        <source>Measure residual scales</source>
        <translation>Residuenskalen messen</translation>
    </message>
    <message>
        <source>Weigh colour by its fit</source>
        <translation>Farbe nach Passung gewichten</translation>
    </message>
    <message>
        <source>nr+icp: cut the photometric term&apos;s share where it pulls the pose off the depth&apos;s own optimum</source>
        <translation>nr+icp: den Anteil des photometrischen Terms kürzen, wo er die Pose vom Optimum der Tiefe wegzieht</translation>
    </message>
    <message>
        <source>Turn on when colour and depth are not registered (an uncalibrated camera)</source>
        <translation>Einschalten, wenn Farbe und Tiefe nicht registriert sind (eine unkalibrierte Kamera)</translation>
    </message>
    <message>
        <source>Depth noise grows with distance</source>
        <translation>Tiefenrauschen nach Abstand</translation>
    </message>
    <message>
        <source>Scale each point-to-plane residual with its depth squared, as a structured-light or stereo sensor&apos;s noise grows</source>
        <translation>Jedes Punkt-zu-Ebene-Residuum mit dem Quadrat seiner Tiefe skalieren, wie das Rauschen eines Structured-Light- oder Stereo-Sensors wächst</translation>
    </message>
    <message>
        <source>Turn on for real structured-light or stereo cameras (a Kinect)</source>
        <translation>Für echte Structured-Light- oder Stereo-Kameras einschalten (eine Kinect)</translation>
    </message>
    <message>
        <source>Weigh the tracker&apos;s terms by their measured residuals (after a few frames) instead of the scales above</source>
        <translation>Die Terme des Trackers nach ihren gemessenen Residuen gewichten (nach einigen Bildern) statt nach den obigen Skalen</translation>
    </message>
    <message>
        <source>Keep on; off to use the fixed scales above</source>
        <translation>Eingeschaltet lassen; aus, um die festen Skalen oben zu verwenden</translation>
    </message>
    <message>
        <source>Least depth residual scale</source>
        <translation>Kleinste Skala des Tiefenresiduums</translation>
    </message>
    <message>
        <source>Smallest point-to-plane scale the measured scales may take</source>
        <translation>Kleinste Punkt-zu-Ebene-Skala, die die gemessenen Skalen annehmen dürfen</translation>
    </message>
    <message>
        <source>Raise when very clean depth makes tracking overconfident</source>
        <translation>Erhöhen, wenn sehr saubere Tiefe das Tracking zu selbstsicher macht</translation>
    </message>
    <message>
        <source>Least colour residual scale</source>
        <translation>Kleinste Skala des Farbresiduums</translation>
    </message>
    <message>
        <source>Smallest normalized-radiance scale the measured scales may take</source>
        <translation>Kleinste Skala der normalisierten Radianz, die die gemessenen Skalen annehmen dürfen</translation>
    </message>
    <message>
        <source>Raise when very clean colour makes tracking overconfident</source>
        <translation>Erhöhen, wenn sehr saubere Farbe das Tracking zu selbstsicher macht</translation>
    </message>
    <message>
        <source>Outlier threshold</source>
        <translation>Ausreißerschwelle</translation>
    </message>
    <message>
        <source>Huber threshold, in units of the scales above</source>
        <translation>Huber-Schwelle, in Einheiten der obigen Skalen</translation>
    </message>
    <message>
        <source>Lower when moving objects disturb tracking</source>
        <translation>Niedriger, wenn bewegte Objekte das Tracking stören</translation>
    </message>
    <message>
        <source>Largest point match distance</source>
        <translation>Größter Abstand zugeordneter Punkte</translation>
    </message>
    <message>
        <source>ICP pairs farther apart are not matched</source>
        <translation>Weiter auseinanderliegende ICP-Paare werden nicht zugeordnet</translation>
    </message>
    <message>
        <source>Raise for fast motion, lower for clutter</source>
        <translation>Erhöhen für schnelle Bewegung, senken bei vielen Gegenständen</translation>
    </message>
    <message>
        <source>Largest normal difference</source>
        <translation>Größter Unterschied der Normalen</translation>
    </message>
    <message>
        <source>ICP pairs whose normals differ more are not matched</source>
        <translation>ICP-Paare, deren Normalen stärker abweichen, werden nicht zugeordnet</translation>
    </message>
    <message>
        <source>Raise for noisy normals</source>
        <translation>Erhöhen für verrauschte Normalen</translation>
    </message>
    <message>
        <source>Least matched share</source>
        <translation>Kleinster zugeordneter Anteil</translation>
    </message>
    <message>
        <source>A frame matching fewer of its pixels than this is lost</source>
        <translation>Ein Bild, das weniger seiner Pixel zuordnet, gilt als verloren</translation>
    </message>
    <message>
        <source>Lower for scenes with little overlap between frames; raise to refuse doubtful frames</source>
        <translation>Niedriger für Szenen mit wenig Überlappung zwischen Bildern; höher, um zweifelhafte Bilder abzulehnen</translation>
    </message>
    <message>
        <source>Worst conditioning</source>
        <translation>Schlechteste Kondition</translation>
    </message>
    <message>
        <source>A frame whose system is worse conditioned is lost</source>
        <translation>Ein Bild, dessen Gleichungssystem schlechter konditioniert ist, gilt als verloren</translation>
    </message>
    <message>
        <source>Lower to refuse frames of flat walls that cannot fix every direction</source>
        <translation>Niedriger, um Bilder flacher Wände abzulehnen, die nicht jede Richtung festlegen</translation>
    </message>
    <message>
        <source>Largest jump</source>
        <translation>Größter Sprung</translation>
    </message>
    <message>
        <source>A frame moving farther from its prediction is lost</source>
        <translation>Ein Bild, das sich weiter von seiner Vorhersage entfernt, gilt als verloren</translation>
    </message>
    <message>
        <source>Raise for a fast hand-held camera</source>
        <translation>Erhöhen für eine schnell geführte Handkamera</translation>
    </message>
    <message>
        <source>Largest turn</source>
        <translation>Größte Drehung</translation>
    </message>
    <message>
        <source>A frame turning farther from its prediction is lost</source>
        <translation>Ein Bild, das sich weiter als seine Vorhersage dreht, gilt als verloren</translation>
    </message>
    <message>
        <source>Raise for a fast turning camera</source>
        <translation>Erhöhen für eine schnell drehende Kamera</translation>
    </message>
    <message>
        <source>Residual growth limit</source>
        <translation>Grenze des Residuenanstiegs</translation>
    </message>
    <message>
        <source>A pose whose residual exceeds this many times the scan&apos;s recent median is not fused</source>
        <translation>Eine Pose, deren Residuum so viele Male über dem jüngsten Median des Scans liegt, wird nicht fusioniert</translation>
    </message>
    <message>
        <source>Raise when good frames are refused after a change of scene</source>
        <translation>Erhöhen, wenn nach einem Szenenwechsel gute Bilder abgelehnt werden</translation>
    </message>
    <message>
        <source>Always-good depth residual</source>
        <translation>Stets gutes Tiefenresiduum</translation>
    </message>
    <message>
        <source>Point-to-surface residuals below this always verify</source>
        <translation>Punkt-zu-Fläche-Residuen darunter gelten stets als bestätigt</translation>
    </message>
    <message>
        <source>Raise for noisy depth when good frames are refused</source>
        <translation>Erhöhen für verrauschte Tiefe, wenn gute Bilder abgelehnt werden</translation>
    </message>
    <message>
        <source>Always-good colour residual</source>
        <translation>Stets gutes Farbresiduum</translation>
    </message>
    <message>
        <source>Normalized-radiance residuals below this always verify (no ICP)</source>
        <translation>Residuen der normalisierten Radianz darunter gelten stets als bestätigt (ohne ICP)</translation>
    </message>
    <message>
        <source>Raise for noisy colour when good frames are refused</source>
        <translation>Erhöhen für verrauschte Farbe, wenn gute Bilder abgelehnt werden</translation>
    </message>
    <message>
        <source>Least robust weight</source>
        <translation>Kleinstes robustes Gewicht</translation>
    </message>
    <message>
        <source>A pose whose terms&apos; mean robust weight is lower is not fused</source>
        <translation>Eine Pose, deren mittleres robustes Gewicht der Terme niedriger ist, wird nicht fusioniert</translation>
    </message>
    <message>
        <source>Lower when good frames are refused in clutter</source>
        <translation>Niedriger, wenn in vollen Szenen gute Bilder abgelehnt werden</translation>
    </message>
    <message>
        <source>Exposure disagreement limit</source>
        <translation>Grenze der Belichtungsabweichung</translation>
    </message>
    <message>
        <source>A pose whose exposure estimate departs more from the sensor&apos;s (relative) is not fused</source>
        <translation>Eine Pose, deren Belichtungsschätzung stärker (relativ) von der des Sensors abweicht, wird nicht fusioniert</translation>
    </message>
    <message>
        <source>Raise for a camera whose reported exposure is unreliable</source>
        <translation>Erhöhen für eine Kamera, deren gemeldete Belichtung unzuverlässig ist</translation>
    </message>
    <message>
        <source>Frames to confirm</source>
        <translation>Bilder zur Bestätigung</translation>
    </message>
    <message>
        <source>After a loss, frames that must verify in a row before fusion resumes</source>
        <translation>Nach einem Verlust: Bilder, die nacheinander bestätigt werden müssen, bevor die Fusion fortfährt</translation>
    </message>
    <message>
        <source>More to be surer after a loss, fewer to resume sooner</source>
        <translation>Mehr, um nach einem Verlust sicherer zu sein, weniger, um früher fortzufahren</translation>
    </message>
    <message>
        <source>Depth needed to start</source>
        <translation>Nötige Tiefe zum Start</translation>
    </message>
    <message>
        <source>The first frame with this share of pixels with depth anchors the model</source>
        <translation>Das erste Bild mit diesem Anteil an Pixeln mit Tiefe verankert das Modell</translation>
    </message>
    <message>
        <source>Lower for scenes mostly out of the depth range</source>
        <translation>Niedriger für Szenen, die großteils außerhalb des Tiefenbereichs liegen</translation>
    </message>
    <message>
        <source>Relocalise when lost</source>
        <translation>Bei Verlust relokalisieren</translation>
    </message>
    <message>
        <source>When lost, look for the pose among the scan&apos;s earlier views</source>
        <translation>Bei Verlust die Pose unter früheren Ansichten des Scans suchen</translation>
    </message>
    <message>
        <source>Keep on; off only to study losses</source>
        <translation>Eingeschaltet lassen; aus nur, um Verluste zu untersuchen</translation>
    </message>
    <message>
        <source>Views tried when lost</source>
        <translation>Versuchte Ansichten bei Verlust</translation>
    </message>
    <message>
        <source>Earlier views tried per lost frame</source>
        <translation>Frühere Ansichten, die je verlorenem Bild versucht werden</translation>
    </message>
    <message>
        <source>More to find the place sooner, at more time per lost frame</source>
        <translation>Mehr, um den Ort schneller zu finden, mit mehr Zeit je verlorenem Bild</translation>
    </message>
    <message>
        <source>Keyframe spacing</source>
        <translation>Abstand der Schlüsselbilder</translation>
    </message>
    <message>
        <source>A view is kept for relocalisation after this much motion</source>
        <translation>Eine Ansicht wird nach so viel Bewegung für die Relokalisierung behalten</translation>
    </message>
    <message>
        <source>Lower to keep more views for relocalisation (more memory)</source>
        <translation>Niedriger, um mehr Ansichten für die Relokalisierung zu behalten (mehr Speicher)</translation>
    </message>
    <message>
        <source>Keyframe angle</source>
        <translation>Winkel der Schlüsselbilder</translation>
    </message>
    <message>
        <source>A view is kept for relocalisation after this much turning</source>
        <translation>Eine Ansicht wird nach so viel Drehung für die Relokalisierung behalten</translation>
    </message>
    <message>
        <source>Exposure sample spacing</source>
        <translation>Abstand der Belichtungsstichproben</translation>
    </message>
    <message>
        <source>Every stride-th pixel in x and y is an exposure sample</source>
        <translation>Jedes stride-te Pixel in x und y ist eine Belichtungsstichprobe</translation>
    </message>
    <message>
        <source>Lower for small images, higher for speed</source>
        <translation>Niedriger für kleine Bilder, höher für Geschwindigkeit</translation>
    </message>
    <message>
        <source>Least exposure samples</source>
        <translation>Mindestzahl an Belichtungsstichproben</translation>
    </message>
    <message>
        <source>Fewer matched samples: the exposure ratio stays 1</source>
        <translation>Weniger zugeordnete Stichproben: das Belichtungsverhältnis bleibt 1</translation>
    </message>
    <message>
        <source>Lower for small images</source>
        <translation>Niedriger für kleine Bilder</translation>
    </message>
    <message>
        <source>Patch size</source>
        <translation>Fenstergröße</translation>
    </message>
    <message>
        <source>Side of the local patch, in pixels of the down-sampled image (odd)</source>
        <translation>Seitenlänge des lokalen Fensters, in Pixeln des verkleinerten Bildes (ungerade)</translation>
    </message>
    <message>
        <source>Larger for noisy colour, smaller for fine texture</source>
        <translation>Größer für verrauschte Farbe, kleiner für feine Textur</translation>
    </message>
    <message>
        <source>Patch statistics scale</source>
        <translation>Maßstab der Fensterstatistik</translation>
    </message>
    <message>
        <source>Local statistics on an image down-sampled by this factor</source>
        <translation>Lokale Statistik auf einem um diesen Faktor verkleinerten Bild</translation>
    </message>
    <message>
        <source>Keep 2; 1 for small images</source>
        <translation>2 beibehalten; 1 für kleine Bilder</translation>
    </message>
    <message>
        <source>Least local contrast</source>
        <translation>Kleinster lokaler Kontrast</translation>
    </message>
    <message>
        <source>Floor on the local std, relative to the local mean</source>
        <translation>Untergrenze der lokalen Standardabweichung, relativ zum lokalen Mittelwert</translation>
    </message>
    <message>
        <source>Raise when noise in flat areas disturbs tracking</source>
        <translation>Erhöhen, wenn Rauschen in flachen Bereichen das Tracking stört</translation>
    </message>
    <message>
        <source>Smooth depth</source>
        <translation>Tiefe glätten</translation>
    </message>
    <message>
        <source>Edge-preserving bilateral filter of the depth</source>
        <translation>Kantenerhaltender bilateraler Filter der Tiefe</translation>
    </message>
    <message>
        <source>Keep on; off for clean synthetic depth</source>
        <translation>Eingeschaltet lassen; aus für saubere synthetische Tiefe</translation>
    </message>
    <message>
        <source>Smoothing width</source>
        <translation>Glättungsbreite</translation>
    </message>
    <message>
        <source>Bilateral filter: spatial sigma</source>
        <translation>Bilateraler Filter: räumliches Sigma</translation>
    </message>
    <message>
        <source>Larger for noisy depth</source>
        <translation>Größer für verrauschte Tiefe</translation>
    </message>
    <message>
        <source>Smoothing depth range</source>
        <translation>Tiefenbereich der Glättung</translation>
    </message>
    <message>
        <source>Bilateral filter: range sigma</source>
        <translation>Bilateraler Filter: Wertebereichs-Sigma</translation>
    </message>
    <message>
        <source>Larger for noisy depth, smaller to keep edges</source>
        <translation>Größer für verrauschte Tiefe, kleiner, um Kanten zu erhalten</translation>
    </message>
    <message>
        <source>Smoothing window</source>
        <translation>Glättungsfenster</translation>
    </message>
    <message>
        <source>Bilateral filter: window radius</source>
        <translation>Bilateraler Filter: Fensterradius</translation>
    </message>
    <message>
        <source>Larger with a larger smoothing width</source>
        <translation>Größer bei größerer Glättungsbreite</translation>
    </message>
    <message>
        <source>Depth edge threshold</source>
        <translation>Schwelle für Tiefenkanten</translation>
    </message>
    <message>
        <source>Normals are undefined across larger depth jumps</source>
        <translation>Über größere Tiefensprünge hinweg sind Normalen undefiniert</translation>
    </message>
    <message>
        <source>Raise for noisy depth at a distance</source>
        <translation>Erhöhen für verrauschte Tiefe in der Entfernung</translation>
    </message>
    <message>
        <source>Largest speed</source>
        <translation>Größte Geschwindigkeit</translation>
    </message>
    <message>
        <source>A pose implying a faster camera since the last accepted one is not fused</source>
        <translation>Eine Pose, die seit der letzten angenommenen eine schnellere Kamera bedeutet, wird nicht fusioniert</translation>
    </message>
    <message>
        <source>Raise for a camera swung or carried faster than this</source>
        <translation>Erhöhen für eine Kamera, die schneller geschwenkt oder getragen wird</translation>
    </message>
    <message>
        <source>Weak-direction hold</source>
        <translation>Halt schwacher Richtungen</translation>
    </message>
    <message>
        <source>Along directions the pixels fix less than this share of the best-fixed one, the motion prediction holds the pose (0: off)</source>
        <translation>In Richtungen, die die Pixel schwächer als diesen Anteil der am besten bestimmten festlegen, hält die Bewegungsvorhersage die Pose (0: aus)</translation>
    </message>
    <message>
        <source>Raise if poses slide along flat walls; lower if smooth but quick moves are tracked late</source>
        <translation>Erhöhen, wenn Posen an ebenen Wänden entlanggleiten; senken, wenn ruhige, aber schnelle Bewegungen verspätet verfolgt werden</translation>
    </message>
</context>
<context>
    <name>ToneMapping</name>
    <message>
        <source>Mantiuk 2008 (display adaptive)</source>
        <translation>Mantiuk 2008 (displayadaptiv)</translation>
    </message>
    <message>
        <source>A global tone curve fitted per frame so that the display shows the scene&apos;s visible contrasts as closely as it can, for the display and viewing conditions below.</source>
        <translation>Eine globale Tonkurve, je Bild so angepasst, dass das Display die sichtbaren Kontraste der Szene so getreu wie möglich zeigt, für das Display und die Betrachtungsbedingungen unten.</translation>
    </message>
    <message>
        <source>Display gamma</source>
        <translation>Display-Gamma</translation>
    </message>
    <message>
        <source>Gamma of the display&apos;s response.</source>
        <translation>Gamma der Antwort des Displays.</translation>
    </message>
    <message>
        <source>Peak luminance</source>
        <translation>Spitzenleuchtdichte</translation>
    </message>
    <message>
        <source>Luminance of display white.</source>
        <translation>Leuchtdichte von Displayweiß.</translation>
    </message>
    <message>
        <source>Black level</source>
        <translation>Schwarzwert</translation>
    </message>
    <message>
        <source>Luminance of display black in a dark room.</source>
        <translation>Leuchtdichte von Displayschwarz in einem dunklen Raum.</translation>
    </message>
    <message>
        <source>Screen reflectivity</source>
        <translation>Bildschirmreflexion</translation>
    </message>
    <message>
        <source>Fraction of ambient light the screen reflects.</source>
        <translation>Anteil des Umgebungslichts, den der Bildschirm reflektiert.</translation>
    </message>
    <message>
        <source>Ambient light</source>
        <translation>Umgebungslicht</translation>
    </message>
    <message>
        <source>Illuminance falling on the screen.</source>
        <translation>Beleuchtungsstärke auf dem Bildschirm.</translation>
    </message>
    <message>
        <source>Pixels per degree</source>
        <translation>Pixel je Grad</translation>
    </message>
    <message>
        <source>Display resolution at the viewing distance; sets the analysed bands.</source>
        <translation>Displayauflösung im Betrachtungsabstand; bestimmt die analysierten Frequenzbänder.</translation>
    </message>
    <message>
        <source>Viewing distance</source>
        <translation>Betrachtungsabstand</translation>
    </message>
    <message>
        <source>Distance from the eye to the screen.</source>
        <translation>Abstand vom Auge zum Bildschirm.</translation>
    </message>
    <message>
        <source>Contrast enhancement</source>
        <translation>Kontrastverstärkung</translation>
    </message>
    <message>
        <source>1 preserves the scene&apos;s contrast; above 1 enhances it.</source>
        <translation>1 erhält den Kontrast der Szene; über 1 verstärkt ihn.</translation>
    </message>
    <message>
        <source>Saturation</source>
        <translation>Sättigung</translation>
    </message>
    <message>
        <source>1 preserves colour appearance; below 1 desaturates.</source>
        <translation>1 erhält das Farberscheinungsbild; unter 1 entsättigt.</translation>
    </message>
    <message>
        <source>Scene adaptation</source>
        <translation>Szenenadaptation</translation>
    </message>
    <message>
        <source>Luminance the original scene is seen at; 0 takes each region&apos;s own luminance.</source>
        <translation>Leuchtdichte, bei der die ursprüngliche Szene gesehen wird; 0 nimmt die eigene Leuchtdichte jedes Bereichs.</translation>
    </message>
    <message>
        <source>Contrast masking</source>
        <translation>Kontrastmaskierung</translation>
    </message>
    <message>
        <source>Model the lower visibility of contrast on contrast.</source>
        <translation>Die geringere Sichtbarkeit von Kontrast auf Kontrast modellieren.</translation>
    </message>
    <message>
        <source>Luminance masking</source>
        <translation>Leuchtdichtemaskierung</translation>
    </message>
    <message>
        <source>Model the lower sensitivity at low luminance.</source>
        <translation>Die geringere Empfindlichkeit bei niedriger Leuchtdichte modellieren.</translation>
    </message>
    <message>
        <source>Contrast sensitivity</source>
        <translation>Kontrastempfindlichkeit</translation>
    </message>
    <message>
        <source>Weigh contrasts by the eye&apos;s sensitivity to their frequency.</source>
        <translation>Kontraste nach der Empfindlichkeit des Auges für ihre Frequenz gewichten.</translation>
    </message>
    <message>
        <source>Temporal filter</source>
        <translation>Zeitlicher Filter</translation>
    </message>
    <message>
        <source>For video: low-pass the curve over time so the view does not flicker.</source>
        <translation>Für Video: die Kurve zeitlich tiefpassfiltern, damit die Ansicht nicht flackert.</translation>
    </message>
    <message>
        <source>Filter cut-off</source>
        <translation>Grenzfrequenz</translation>
    </message>
    <message>
        <source>Cut-off frequency of the curve&apos;s time filter.</source>
        <translation>Grenzfrequenz des zeitlichen Filters der Kurve.</translation>
    </message>
    <message>
        <source>LCD, office</source>
        <translation>LCD, Büro</translation>
    </message>
    <message>
        <source>LCD</source>
        <translation>LCD</translation>
    </message>
    <message>
        <source>LCD, bright</source>
        <translation>LCD, hell</translation>
    </message>
    <message>
        <source>CRT</source>
        <translation>CRT</translation>
    </message>
    <message>
        <source>Mantiuk 2006 (contrast domain)</source>
        <translation>Mantiuk 2006 (Kontrastbereich)</translation>
    </message>
    <message>
        <source>Local contrast at every scale compressed in a perceptual response space: details stay visible while large luminance differences shrink to fit the display.</source>
        <translation>Lokaler Kontrast auf jeder Skala, komprimiert in einem wahrnehmungsbasierten Antwortraum: Details bleiben sichtbar, während große Leuchtdichteunterschiede schrumpfen, bis sie auf das Display passen.</translation>
    </message>
    <message>
        <source>Contrast factor</source>
        <translation>Kontrastfaktor</translation>
    </message>
    <message>
        <source>Mapping: scale of the contrast response (smaller compresses more). Equalisation: its strength.</source>
        <translation>Abbildung: Maßstab der Kontrastantwort (kleiner komprimiert stärker). Ausgleich: seine Stärke.</translation>
    </message>
    <message>
        <source>Contrast equalisation</source>
        <translation>Kontrastausgleich</translation>
    </message>
    <message>
        <source>Flatten the histogram of contrasts instead of scaling them (sharper, less natural).</source>
        <translation>Das Histogramm der Kontraste ebnen, statt sie zu skalieren (schärfer, weniger natürlich).</translation>
    </message>
    <message>
        <source>Exponent of the colour ratios: below 1 desaturates.</source>
        <translation>Exponent der Farbverhältnisse: unter 1 entsättigt.</translation>
    </message>
    <message>
        <source>Detail</source>
        <translation>Detail</translation>
    </message>
    <message>
        <source>Above 1 treats contrasts as larger: stronger local detail.</source>
        <translation>Über 1 behandelt Kontraste als größer: stärkere lokale Details.</translation>
    </message>
    <message>
        <source>Solver iterations</source>
        <translation>Solver-Iterationen</translation>
    </message>
    <message>
        <source>Most conjugate-gradient iterations per frame.</source>
        <translation>Höchstzahl der Iterationen des konjugierten Gradienten je Bild.</translation>
    </message>
    <message>
        <source>Reinhard (global)</source>
        <translation>Reinhard (global)</translation>
    </message>
    <message>
        <source>The photographic operator: the image&apos;s log-average luminance maps to the key, then L / (1 + L).</source>
        <translation>Der fotografische Operator: die logarithmisch gemittelte Leuchtdichte des Bildes wird auf den Schlüsselwert abgebildet, dann L / (1 + L).</translation>
    </message>
    <message>
        <source>Key</source>
        <translation>Schlüsselwert</translation>
    </message>
    <message>
        <source>Display value the log-average luminance maps to.</source>
        <translation>Displaywert, auf den die logarithmisch gemittelte Leuchtdichte abgebildet wird.</translation>
    </message>
    <message>
        <source>Exposure</source>
        <translation>Belichtung</translation>
    </message>
    <message>
        <source>Brightness change, in stops.</source>
        <translation>Helligkeitsänderung in Blendenstufen.</translation>
    </message>
    <message>
        <source>Automatic key</source>
        <translation>Automatischer Schlüsselwert</translation>
    </message>
    <message>
        <source>Scale each frame so that its log-average luminance is mid-grey (follows auto exposure).</source>
        <translation>Jedes Bild so skalieren, dass seine logarithmisch gemittelte Leuchtdichte mittelgrau ist (folgt der Belichtungsautomatik).</translation>
    </message>
    <message>
        <source>Exposure and gamma</source>
        <translation>Belichtung und Gamma</translation>
    </message>
    <message>
        <source>A scale in stops, clipped at white, with an extra gamma on top of the display&apos;s.</source>
        <translation>Eine Skalierung in Blendenstufen, bei Weiß abgeschnitten, mit einem zusätzlichen Gamma über dem des Displays.</translation>
    </message>
    <message>
        <source>Gamma</source>
        <translation>Gamma</translation>
    </message>
    <message>
        <source>Extra gamma: above 1 lifts the darks.</source>
        <translation>Zusätzliches Gamma: über 1 hellt die Tiefen auf.</translation>
    </message>
    <message>
        <source>Linear</source>
        <translation>Linear</translation>
    </message>
    <message>
        <source>Radiance scaled and clipped at white: what was measured, clipping included.</source>
        <translation>Radianz skaliert und bei Weiß abgeschnitten: was gemessen wurde, Übersteuerung eingeschlossen.</translation>
    </message>
    <message>
        <source>Brightness hold</source>
        <translation>Helligkeit halten</translation>
    </message>
    <message>
        <source>For video: up to this many stops, the time filter holds the view&apos;s mean brightness steady while the camera turns to brighter or darker surfaces, and lets it adapt at the pace below. 0 turns it off.</source>
        <translation>Für Video: Bis zu so vielen Blendenstufen hält der Zeitfilter die mittlere Helligkeit der Ansicht ruhig, während sich die Kamera helleren oder dunkleren Flächen zuwendet, und lässt sie sich im unten eingestellten Tempo anpassen. 0 schaltet es aus.</translation>
    </message>
    <message>
        <source>Brightness adaptation</source>
        <translation>Helligkeitsanpassung</translation>
    </message>
    <message>
        <source>Cut-off frequency of the held brightness: at 0.1 Hz the view adapts to what is in view over about three seconds.</source>
        <translation>Grenzfrequenz der gehaltenen Helligkeit: Bei 0,1 Hz passt sich die Ansicht in etwa drei Sekunden an das an, was im Bild ist.</translation>
    </message>
</context>
<context>
    <name>hdrf::EngineText</name>
    <message>
        <source>%1</source>
        <comment>an engine message, quoted as written (English)</comment>
        <translation>„%1“</translation>
    </message>
</context>
<context>
    <name>hdrf::gui::ExportDialog</name>
    <message>
        <source>Export textured HDR asset</source>
        <translation>Texturiertes HDR-Asset exportieren</translation>
    </message>
    <message>
        <source>Browse…</source>
        <translation>Durchsuchen…</translation>
    </message>
    <message>
        <source>Export into</source>
        <translation>Exportieren nach</translation>
    </message>
    <message>
        <source>Folder</source>
        <translation>Ordner</translation>
    </message>
    <message>
        <source>PLY (per-vertex radiance)</source>
        <translation>PLY (Radianz je Vertex)</translation>
    </message>
    <message>
        <source>OBJ + MTL (EXR texture)</source>
        <translation>OBJ + MTL (EXR-Textur)</translation>
    </message>
    <message>
        <source>glTF binary (PNG texture)</source>
        <translation>glTF binär (PNG-Textur)</translation>
    </message>
    <message>
        <source>Formats</source>
        <translation>Formate</translation>
    </message>
    <message>
        <source>Z up (Blender)</source>
        <translation>Z oben (Blender)</translation>
    </message>
    <message>
        <source>Y up</source>
        <translation>Y oben</translation>
    </message>
    <message>
        <source>Up axis</source>
        <translation>Achse nach oben</translation>
    </message>
    <message>
        <source> mm per texel</source>
        <translation> mm je Texel</translation>
    </message>
    <message>
        <source>Texture density</source>
        <translation>Texturdichte</translation>
    </message>
    <message>
        <source>keep all</source>
        <translation>alle behalten</translation>
    </message>
    <message>
        <source>Triangle budget</source>
        <translation>Dreiecksbudget</translation>
    </message>
    <message>
        <source>Render (EXR with alpha and depth)</source>
        <translation>Rendering (EXR mit Alpha und Tiefe)</translation>
    </message>
    <message>
        <source>Render</source>
        <translation>Rendering</translation>
    </message>
    <message>
        <source>Tone mapping</source>
        <translation>Tone-Mapping</translation>
    </message>
    <message>
        <source>The model is cleaned, levelled, unwrapped and textured from the scan&apos;s keyframes.</source>
        <translation>Das Modell wird bereinigt, ausgerichtet, abgewickelt und aus den Schlüsselbildern des Scans texturiert.</translation>
    </message>
    <message>
        <source>The preview appears here when the export is done.</source>
        <translation>Die Vorschau erscheint hier, wenn der Export fertig ist.</translation>
    </message>
    <message>
        <source>Export</source>
        <translation>Exportieren</translation>
    </message>
    <message>
        <source>Cancel export</source>
        <translation>Export abbrechen</translation>
    </message>
    <message>
        <source>Close</source>
        <translation>Schließen</translation>
    </message>
    <message>
        <source>Cancelling…</source>
        <translation>Wird abgebrochen…</translation>
    </message>
    <message>
        <source>Cannot export: %1</source>
        <translation>Export nicht möglich: %1</translation>
    </message>
    <message>
        <source>Choose a folder to export into.</source>
        <translation>Wählen Sie einen Ordner für den Export.</translation>
    </message>
    <message>
        <source>Exporting…</source>
        <translation>Wird exportiert…</translation>
    </message>
    <message>
        <source>Exporting: %1</source>
        <translation>Export: %1</translation>
    </message>
</context>
<context>
    <name>hdrf::gui::ExposurePlot</name>
    <message>
        <source>Exposure ratio to the first frame, in stops: estimated by the engine (cyan) and reported by the sensor (orange)</source>
        <translation>Belichtungsverhältnis zum ersten Bild, in Blendenstufen: von der Engine geschätzt (cyan) und vom Sensor gemeldet (orange)</translation>
    </message>
    <message>
        <source>Exposure, stops</source>
        <translation>Belichtung, Blendenstufen</translation>
    </message>
    <message>
        <source>estimated</source>
        <translation>geschätzt</translation>
    </message>
    <message>
        <source>reported</source>
        <translation>gemeldet</translation>
    </message>
    <message>
        <source>last %1 frames</source>
        <translation>letzte %1 Bilder</translation>
    </message>
</context>
<context>
    <name>hdrf::gui::ImageView</name>
    <message>
        <source>%1: no frame yet</source>
        <translation>%1: noch kein Bild</translation>
    </message>
    <message>
        <source>Save %1 as PNG…</source>
        <translation>%1 als PNG speichern…</translation>
    </message>
    <message>
        <source>Save %1 as OpenEXR (HDR)…</source>
        <translation>%1 als OpenEXR (HDR) speichern…</translation>
    </message>
    <message>
        <source>OpenEXR (*.exr)</source>
        <translation>OpenEXR (*.exr)</translation>
    </message>
    <message>
        <source>PNG (*.png)</source>
        <translation>PNG (*.png)</translation>
    </message>
    <message>
        <source>Saved %1</source>
        <translation>Gespeichert: %1</translation>
    </message>
    <message>
        <source>Save failed</source>
        <translation>Speichern fehlgeschlagen</translation>
    </message>
</context>
<context>
    <name>hdrf::gui::MainWindow</name>
    <message>
        <source>HDRFusion Studio</source>
        <translation>HDRFusion Studio</translation>
    </message>
    <message>
        <source>cancelled</source>
        <translation>abgebrochen</translation>
    </message>
    <message>
        <source>Export</source>
        <translation>Exportieren</translation>
    </message>
    <message>
        <source>HDRFusion Studio — %1</source>
        <translation>HDRFusion Studio — %1</translation>
    </message>
    <message>
        <source>HDRFusion Studio — recovered scan (not saved)</source>
        <translation>HDRFusion Studio — wiederhergestellter Scan (nicht gespeichert)</translation>
    </message>
    <message>
        <source>Save the scan as a project</source>
        <translation>Scan als Projekt speichern</translation>
    </message>
    <message>
        <source>HDRFusion projects (*.hdrproj)</source>
        <translation>HDRFusion-Projekte (*.hdrproj)</translation>
    </message>
    <message>
        <source>Recover a scan</source>
        <translation>Scan wiederherstellen</translation>
    </message>
    <message>
        <source>A scan that did not finish was autosaved on %1:
%2

Open it to continue or export it?</source>
        <translation>Ein nicht beendeter Scan wurde am %1 automatisch gesichert:
%2

Öffnen, um ihn fortzusetzen oder zu exportieren?</translation>
    </message>
    <message>
        <source>Open</source>
        <translation>Öffnen</translation>
    </message>
    <message>
        <source>Delete it</source>
        <translation>Löschen</translation>
    </message>
    <message>
        <source>Later</source>
        <translation>Später</translation>
    </message>
    <message>
        <source>Source</source>
        <translation>Quelle</translation>
    </message>
    <message>
        <source>Sequence folder…</source>
        <translation>Sequenzordner…</translation>
    </message>
    <message>
        <source>Recorded sequence</source>
        <translation>Aufgenommene Sequenz</translation>
    </message>
    <message>
        <source>Start</source>
        <translation>Start</translation>
    </message>
    <message>
        <source>Pause</source>
        <translation>Pause</translation>
    </message>
    <message>
        <source>Stop</source>
        <translation>Stopp</translation>
    </message>
    <message>
        <source>Reset</source>
        <translation>Zurücksetzen</translation>
    </message>
    <message>
        <source>Engine (applies on Reset)</source>
        <translation>Engine (gilt nach Zurücksetzen)</translation>
    </message>
    <message>
        <source>Tone mapping (OpenColorIO %1 / %2)</source>
        <translation>Tone-Mapping (OpenColorIO %1 / %2)</translation>
    </message>
    <message>
        <source>Controls</source>
        <translation>Steuerung</translation>
    </message>
    <message>
        <source>Status</source>
        <translation>Status</translation>
    </message>
    <message>
        <source>Live camera</source>
        <translation>Live-Kamera</translation>
    </message>
    <message>
        <source>Resume</source>
        <translation>Fortsetzen</translation>
    </message>
    <message>
        <source>Live cameras are unavailable: %1</source>
        <translation>Live-Kameras sind nicht verfügbar: %1</translation>
    </message>
    <message>
        <source>Camera connected: %1</source>
        <translation>Kamera verbunden: %1</translation>
    </message>
    <message>
        <source>Camera disconnected: %1</source>
        <translation>Kamera getrennt: %1</translation>
    </message>
    <message>
        <source>&amp;File</source>
        <translation>&amp;Datei</translation>
    </message>
    <message>
        <source>&amp;Export</source>
        <translation>&amp;Exportieren</translation>
    </message>
    <message>
        <source>Textured HDR asset (OBJ, glTF, OpenEXR)…</source>
        <translation>Texturiertes HDR-Asset (OBJ, glTF, OpenEXR)…</translation>
    </message>
    <message>
        <source>HDR mesh (PLY)…</source>
        <translation>HDR-Mesh (PLY)…</translation>
    </message>
    <message>
        <source>Export HDR mesh</source>
        <translation>HDR-Mesh exportieren</translation>
    </message>
    <message>
        <source>PLY (*.ply)</source>
        <translation>PLY (*.ply)</translation>
    </message>
    <message>
        <source>Extracting and writing the mesh…</source>
        <translation>Mesh wird extrahiert und geschrieben…</translation>
    </message>
    <message>
        <source>Cancel</source>
        <translation>Abbrechen</translation>
    </message>
    <message>
        <source>Trajectory (TUM)…</source>
        <translation>Trajektorie (TUM)…</translation>
    </message>
    <message>
        <source>Export trajectory</source>
        <translation>Trajektorie exportieren</translation>
    </message>
    <message>
        <source>Model render (OpenEXR)…</source>
        <translation>Modell-Rendering (OpenEXR)…</translation>
    </message>
    <message>
        <source>Export model render</source>
        <translation>Modell-Rendering exportieren</translation>
    </message>
    <message>
        <source>OpenEXR (*.exr)</source>
        <translation>OpenEXR (*.exr)</translation>
    </message>
    <message>
        <source>&amp;Open project…</source>
        <translation>Projekt ö&amp;ffnen…</translation>
    </message>
    <message>
        <source>Open a scan project</source>
        <translation>Scan-Projekt öffnen</translation>
    </message>
    <message>
        <source>&amp;Save project</source>
        <translation>Projekt &amp;speichern</translation>
    </message>
    <message>
        <source>Save project &amp;as…</source>
        <translation>Projekt speichern &amp;unter…</translation>
    </message>
    <message>
        <source>Save window screenshot…</source>
        <translation>Fenster-Screenshot speichern…</translation>
    </message>
    <message>
        <source>Screenshot</source>
        <translation>Screenshot</translation>
    </message>
    <message>
        <source>PNG (*.png)</source>
        <translation>PNG (*.png)</translation>
    </message>
    <message>
        <source>&amp;Quit</source>
        <translation>&amp;Beenden</translation>
    </message>
    <message>
        <source>&amp;Scan</source>
        <translation>&amp;Scan</translation>
    </message>
    <message>
        <source>Reset (apply engine settings)</source>
        <translation>Zurücksetzen (Engine-Einstellungen anwenden)</translation>
    </message>
    <message>
        <source>&amp;Tools</source>
        <translation>&amp;Werkzeuge</translation>
    </message>
    <message>
        <source>Calibrate camera…</source>
        <translation>Kamera kalibrieren…</translation>
    </message>
    <message>
        <source>&amp;View</source>
        <translation>&amp;Ansicht</translation>
    </message>
    <message>
        <source>Reset 3-D view</source>
        <translation>3D-Ansicht zurücksetzen</translation>
    </message>
    <message>
        <source>Restore default layout</source>
        <translation>Standardanordnung wiederherstellen</translation>
    </message>
    <message>
        <source>Calibration saved: %1 (used from now on for that camera)</source>
        <translation>Kalibrierung gespeichert: %1 (ab jetzt für diese Kamera verwendet)</translation>
    </message>
    <message>
        <source>Engine settings: %1</source>
        <translation>Engine-Einstellungen: %1</translation>
    </message>
    <message>
        <source>A sequence folder, a recording FILE.oni, a live camera openni:device=SERIAL,mode=vga (the Live camera panel fills it in), or synthetic:key=value,... (keys scene=, seed=, frames=, ae=, exposure=, size=)</source>
        <translation>Ein Sequenzordner, eine Aufnahme DATEI.oni, eine Live-Kamera openni:device=SERIENNUMMER,mode=vga (das Live-Kamera-Panel trägt sie ein) oder synthetic:schlüssel=wert,... (Schlüssel scene=, seed=, frames=, ae=, exposure=, size=)</translation>
    </message>
    <message>
        <source>&amp;Language</source>
        <translation>&amp;Sprache</translation>
    </message>
    <message>
        <source>As the system</source>
        <translation>Wie das System</translation>
    </message>
    <message>
        <source>The language changes when the studio starts again.</source>
        <translation>Die Sprache wechselt beim nächsten Start des Studios.</translation>
    </message>
    <message>
        <source>Full surface detail while scanning</source>
        <translation>Volle Oberflächendetails beim Scannen</translation>
    </message>
    <message>
        <source>Off: while a scan runs the 3-D view shows a coarser surface (from every other voxel, a quarter of the triangles; every fourth where the display cannot draw that quickly), which leaves more of the processor to the scan; the whole surface follows when the scan stops</source>
        <translation>Aus: Während ein Scan läuft, zeigt die 3-D-Ansicht eine gröbere Oberfläche (aus jedem zweiten Voxel, ein Viertel der Dreiecke; aus jedem vierten, wo die Anzeige nicht so schnell zeichnen kann), die dem Scan mehr vom Prozessor lässt; die ganze Oberfläche folgt, wenn der Scan anhält</translation>
    </message>
    <message>
        <source>&amp;Help</source>
        <translation>&amp;Hilfe</translation>
    </message>
    <message>
        <source>Scanning a room</source>
        <translation>Einen Raum scannen</translation>
    </message>
</context>
<context>
    <name>hdrf::gui::ScanWorker</name>
    <message>
        <source>the source was changed</source>
        <translation>die Quelle wurde geändert</translation>
    </message>
    <message>
        <source>Autosave failed (the scan goes on): %1</source>
        <translation>Automatische Sicherung fehlgeschlagen (der Scan läuft weiter): %1</translation>
    </message>
    <message>
        <source>Nothing to save: no frame has been scanned yet</source>
        <translation>Nichts zu speichern: noch kein Bild gescannt</translation>
    </message>
    <message>
        <source>Saved %1 frames to %2 (%L3 MiB)</source>
        <translation>%1 Bilder in %2 gespeichert (%L3 MiB)</translation>
    </message>
    <message>
        <source>Cannot save the project: %1</source>
        <translation>Projekt kann nicht gespeichert werden: %1</translation>
    </message>
    <message>
        <source>Opened %1: %2 frames</source>
        <translation>%1 geöffnet: %2 Bilder</translation>
    </message>
    <message>
        <source> — its source has another camera now: choose the source it was scanned with to continue</source>
        <translation> — seine Quelle hat jetzt eine andere Kamera: wählen Sie die Quelle, mit der gescannt wurde, um fortzufahren</translation>
    </message>
    <message>
        <source> — Start continues after frame %1</source>
        <translation> — Start setzt nach Bild %1 fort</translation>
    </message>
    <message>
        <source> — its source has no frames left</source>
        <translation> — seine Quelle hat keine Bilder mehr</translation>
    </message>
    <message>
        <source> — Start continues from the first frame of %1, which must be where the scan stopped</source>
        <translation> — Start setzt mit dem ersten Bild von %1 fort, das dort liegen muss, wo der Scan aufhörte</translation>
    </message>
    <message>
        <source> — its source (%1) cannot be opened: %2</source>
        <translation> — seine Quelle (%1) kann nicht geöffnet werden: %2</translation>
    </message>
    <message>
        <source>Cannot open the project: %1</source>
        <translation>Projekt kann nicht geöffnet werden: %1</translation>
    </message>
    <message>
        <source>Opening the camera…</source>
        <translation>Kamera wird geöffnet…</translation>
    </message>
    <message>
        <source>Ready: %1</source>
        <translation>Bereit: %1</translation>
    </message>
    <message>
        <source>Live preview: %1 (Start scans)</source>
        <translation>Live-Vorschau: %1 (Start scannt)</translation>
    </message>
    <message>
        <source>Cannot open the source: %1</source>
        <translation>Quelle kann nicht geöffnet werden: %1</translation>
    </message>
    <message>
        <source>No source</source>
        <translation>Keine Quelle</translation>
    </message>
    <message>
        <source>No source to continue from: choose one (Source) and Open the project again, or Reset</source>
        <translation>Keine Quelle zum Fortsetzen: wählen Sie eine (Quelle) und öffnen Sie das Projekt erneut, oder setzen Sie zurück</translation>
    </message>
    <message>
        <source>Scanning on the %1</source>
        <translation>Scan auf der %1</translation>
    </message>
    <message>
        <source>Paused after %1 frames</source>
        <translation>Angehalten nach %1 Bildern</translation>
    </message>
    <message>
        <source>Stopped; the model of %1 frames is kept</source>
        <translation>Gestoppt; das Modell aus %1 Bildern bleibt erhalten</translation>
    </message>
    <message>
        <source>Reset: empty model</source>
        <translation>Zurückgesetzt: leeres Modell</translation>
    </message>
    <message>
        <source>Finished: %1 frames</source>
        <translation>Fertig: %1 Bilder</translation>
    </message>
    <message>
        <source>Scan paused at frame %1: %2. The model so far is kept.</source>
        <translation>Scan bei Bild %1 angehalten: %2. Das bisherige Modell bleibt erhalten.</translation>
    </message>
    <message>
        <source>Paused (error)</source>
        <translation>Angehalten (Fehler)</translation>
    </message>
    <message>
        <source>Live preview: %1</source>
        <translation>Live-Vorschau: %1</translation>
    </message>
    <message>
        <source>Nothing to record: open a live camera first</source>
        <translation>Nichts aufzunehmen: öffnen Sie zuerst eine Live-Kamera</translation>
    </message>
    <message>
        <source>Already recording to %1</source>
        <translation>Nimmt bereits nach %1 auf</translation>
    </message>
    <message>
        <source>Recording to %1</source>
        <translation>Aufnahme nach %1</translation>
    </message>
    <message>
        <source>Cannot record: %1</source>
        <translation>Aufnahme nicht möglich: %1</translation>
    </message>
    <message>
        <source>Recorded %1 frames (%L2 MB, %L3 s, %4 dropped) to %5</source>
        <translation>%1 Bilder aufgenommen (%L2 MB, %L3 s, %4 verworfen) nach %5</translation>
    </message>
    <message>
        <source>Recording ended early: %1. %2</source>
        <translation>Aufnahme vorzeitig beendet: %1. %2</translation>
    </message>
    <message>
        <source>Recording ended: %1. %2</source>
        <translation>Aufnahme beendet: %1. %2</translation>
    </message>
    <message>
        <source>Recorded %1</source>
        <translation>Aufgenommen: %1</translation>
    </message>
    <message>
        <source>Camera settings: no live camera is open</source>
        <translation>Kameraeinstellungen: keine Live-Kamera geöffnet</translation>
    </message>
    <message>
        <source>Camera: auto exposure %1, white balance %2, exposure %3, gain %4</source>
        <translation>Kamera: Belichtungsautomatik %1, Weißabgleich %2, Belichtung %3, Verstärkung %4</translation>
    </message>
    <message>
        <source>on</source>
        <translation>an</translation>
    </message>
    <message>
        <source>off</source>
        <translation>aus</translation>
    </message>
    <message>
        <source>auto</source>
        <translation>automatisch</translation>
    </message>
    <message>
        <source>fixed</source>
        <translation>fest</translation>
    </message>
    <message>
        <source>Camera settings: %1</source>
        <translation>Kameraeinstellungen: %1</translation>
    </message>
    <message>
        <source>Listing cameras: %1</source>
        <translation>Kameras auflisten: %1</translation>
    </message>
    <message>
        <source>the camera</source>
        <translation>die Kamera</translation>
    </message>
    <message>
        <source>%1 was unplugged</source>
        <translation>%1 wurde abgezogen</translation>
    </message>
    <message>
        <source>Camera %1 was unplugged: the scan is paused after %2 frames and the model is kept. Plug it back in to resume.</source>
        <translation>Kamera %1 wurde abgezogen: der Scan ist nach %2 Bildern angehalten, das Modell bleibt erhalten. Stecken Sie sie wieder ein, um fortzusetzen.</translation>
    </message>
    <message>
        <source>Camera %1 was unplugged. Plug it back in to continue.</source>
        <translation>Kamera %1 wurde abgezogen. Stecken Sie sie wieder ein, um fortzufahren.</translation>
    </message>
    <message>
        <source>Camera unplugged; waiting for it to come back</source>
        <translation>Kamera abgezogen; warte auf ihre Rückkehr</translation>
    </message>
    <message>
        <source>Camera %1 was connected, but this scan was made with %2: plug that one back in, or Reset to start a new scan</source>
        <translation>Kamera %1 wurde verbunden, aber dieser Scan wurde mit %2 aufgenommen: stecken Sie jene wieder ein oder setzen Sie zurück, um einen neuen Scan zu beginnen</translation>
    </message>
    <message>
        <source>Camera %1 is back: the scan resumes at frame %2</source>
        <translation>Kamera %1 ist zurück: der Scan setzt bei Bild %2 fort</translation>
    </message>
    <message>
        <source>Scanning (resumed after a reconnect)</source>
        <translation>Scan läuft (nach erneuter Verbindung fortgesetzt)</translation>
    </message>
    <message>
        <source>Camera %1 is back</source>
        <translation>Kamera %1 ist zurück</translation>
    </message>
    <message>
        <source>Live preview (the model of %1 frames is kept; Start continues it)</source>
        <translation>Live-Vorschau (das Modell aus %1 Bildern bleibt erhalten; Start setzt es fort)</translation>
    </message>
    <message>
        <source>The camera came back but could not be reopened: %1</source>
        <translation>Die Kamera kam zurück, konnte aber nicht wieder geöffnet werden: %1</translation>
    </message>
    <message>
        <source>Nothing to export: no model</source>
        <translation>Nichts zu exportieren: kein Modell</translation>
    </message>
    <message>
        <source>Wrote %1 (%2 vertices, %3 triangles)</source>
        <translation>%1 geschrieben (%2 Vertices, %3 Dreiecke)</translation>
    </message>
    <message>
        <source>Mesh export cancelled; nothing was written</source>
        <translation>Mesh-Export abgebrochen; nichts wurde geschrieben</translation>
    </message>
    <message>
        <source>Mesh export: %1</source>
        <translation>Mesh-Export: %1</translation>
    </message>
    <message>
        <source>Wrote %1 (%2 poses)</source>
        <translation>%1 geschrieben (%2 Posen)</translation>
    </message>
    <message>
        <source>Trajectory export: %1</source>
        <translation>Trajektorienexport: %1</translation>
    </message>
    <message>
        <source>Wrote %1</source>
        <translation>%1 geschrieben</translation>
    </message>
    <message>
        <source>OpenEXR export: %1</source>
        <translation>OpenEXR-Export: %1</translation>
    </message>
    <message>
        <source>Nothing to export: scan first</source>
        <translation>Nichts zu exportieren: zuerst scannen</translation>
    </message>
    <message>
        <source>mesh</source>
        <translation>Mesh</translation>
    </message>
    <message>
        <source>Wrote %1 files into %2: %3</source>
        <translation>%1 Dateien nach %2 geschrieben: %3</translation>
    </message>
    <message>
        <source>Note: %1</source>
        <translation>Hinweis: %1</translation>
    </message>
    <message>
        <source>Export cancelled; the folder was left as it was</source>
        <translation>Export abgebrochen; der Ordner blieb unverändert</translation>
    </message>
    <message>
        <source>Export failed: %1</source>
        <translation>Export fehlgeschlagen: %1</translation>
    </message>
    <message>
        <source> — its source has another camera response now (its calibration changed): choose the source it was scanned with to continue</source>
        <translation> — seine Quelle hat jetzt eine andere Kamerakennlinie (ihre Kalibrierung wurde geändert): wählen Sie die Quelle, mit der gescannt wurde, um fortzufahren</translation>
    </message>
</context>
<context>
    <name>hdrf::gui::SensorPanel</name>
    <message>
        <source>Camera</source>
        <translation>Kamera</translation>
    </message>
    <message>
        <source>Refresh</source>
        <translation>Aktualisieren</translation>
    </message>
    <message>
        <source>List the connected cameras again (the list also follows plug events)</source>
        <translation>Die angeschlossenen Kameras erneut auflisten (die Liste folgt auch Ein- und Aussteckereignissen)</translation>
    </message>
    <message>
        <source>VGA 640×480, 30 Hz</source>
        <translation>VGA 640×480, 30 Hz</translation>
    </message>
    <message>
        <source>QVGA 320×240, 30 Hz</source>
        <translation>QVGA 320×240, 30 Hz</translation>
    </message>
    <message>
        <source>Preview</source>
        <translation>Vorschau</translation>
    </message>
    <message>
        <source>Open this camera: its picture shows live; Start scans it</source>
        <translation>Diese Kamera öffnen: ihr Bild erscheint live; Start scannt es</translation>
    </message>
    <message>
        <source>No camera open</source>
        <translation>Keine Kamera geöffnet</translation>
    </message>
    <message>
        <source>Exposure</source>
        <translation>Belichtung</translation>
    </message>
    <message>
        <source>Auto exposure</source>
        <translation>Belichtungsautomatik</translation>
    </message>
    <message>
        <source>Auto white balance</source>
        <translation>Automatischer Weißabgleich</translation>
    </message>
    <message>
        <source> ms</source>
        <translation> ms</translation>
    </message>
    <message>
        <source>Exposure time (auto exposure off); in the device&apos;s raw unit when its profile gives no millisecond unit</source>
        <translation>Belichtungszeit (Belichtungsautomatik aus); in der Roheinheit des Geräts, wenn sein Profil keine Millisekunden-Einheit angibt</translation>
    </message>
    <message>
        <source>Analogue gain; 100 is unity</source>
        <translation>Analoge Verstärkung; 100 ist Eins</translation>
    </message>
    <message>
        <source>Gain</source>
        <translation>Verstärkung</translation>
    </message>
    <message>
        <source>Record</source>
        <translation>Aufnahme</translation>
    </message>
    <message>
        <source>a new folder in ~/HDRFusion/recordings</source>
        <translation>ein neuer Ordner in ~/HDRFusion/recordings</translation>
    </message>
    <message>
        <source>A new sequence folder (colour PNG, 16-bit depth, exposure.txt, sensor.json), or FILE.oni</source>
        <translation>Ein neuer Sequenzordner (Farb-PNG, 16-Bit-Tiefe, exposure.txt, sensor.json) oder DATEI.oni</translation>
    </message>
    <message>
        <source>…</source>
        <translation>…</translation>
    </message>
    <message>
        <source>Choose where to record</source>
        <translation>Aufnahmeziel wählen</translation>
    </message>
    <message>
        <source>Record to (a new folder, or FILE.oni)</source>
        <translation>Aufnehmen nach (ein neuer Ordner oder DATEI.oni)</translation>
    </message>
    <message>
        <source>Stop recording</source>
        <translation>Aufnahme beenden</translation>
    </message>
    <message>
        <source>Starting: %1</source>
        <translation>Wird gestartet: %1</translation>
    </message>
    <message>
        <source>This device did not answer (in use by another program?)</source>
        <translation>Dieses Gerät hat nicht geantwortet (von einem anderen Programm belegt?)</translation>
    </message>
    <message>
        <source>Calibrated: its own profile is used</source>
        <translation>Kalibriert: sein eigenes Profil wird verwendet</translation>
    </message>
    <message>
        <source>Not calibrated: the built-in Xtion profile is used; its response is not this camera&apos;s own (Tools → Calibrate camera… for true radiance)</source>
        <translation>Nicht kalibriert: das eingebaute Xtion-Profil wird verwendet; seine Antwortkurve ist nicht die dieser Kamera (Werkzeuge → Kamera kalibrieren… für echte Radianz)</translation>
    </message>
    <message>
        <source> (open)</source>
        <translation> (geöffnet)</translation>
    </message>
    <message>
        <source>No camera connected</source>
        <translation>Keine Kamera angeschlossen</translation>
    </message>
    <message>
        <source> (raw unit)</source>
        <translation> (Roheinheit)</translation>
    </message>
    <message>
        <source>no camera settings (exposure cannot be controlled)</source>
        <translation>keine Kameraeinstellungen (die Belichtung lässt sich nicht steuern)</translation>
    </message>
    <message>
        <source>auto exposure (the engine estimates each frame&apos;s)</source>
        <translation>Belichtungsautomatik (die Engine schätzt die jedes Bildes)</translation>
    </message>
    <message>
        <source>exposure %L1 ms, gain %L2</source>
        <translation>Belichtung %L1 ms, Verstärkung %L2</translation>
    </message>
    <message>
        <source>exposure %1 (raw), gain %2</source>
        <translation>Belichtung %1 (roh), Verstärkung %2</translation>
    </message>
    <message>
        <source>%1: %2; %L3 frames/s; %4 dropped</source>
        <translation>%1: %2; %L3 Bilder/s; %4 verworfen</translation>
    </message>
    <message>
        <source>Dropped: frames the camera sent that were not read in time (the scan is slower than the camera, or the link lost them)</source>
        <translation>Verworfen: Bilder, die die Kamera sandte, die aber nicht rechtzeitig gelesen wurden (der Scan ist langsamer als die Kamera, oder die Verbindung hat sie verloren)</translation>
    </message>
    <message>
        <source>Recording to %1: %2 frames, %L3 MB, %L4 s, %5 dropped</source>
        <translation>Aufnahme nach %1: %2 Bilder, %L3 MB, %L4 s, %5 verworfen</translation>
    </message>
</context>
<context>
    <name>hdrf::gui::SettingsForm</name>
    <message>
        <source>Show expert settings</source>
        <translation>Experteneinstellungen zeigen</translation>
    </message>
    <message>
        <source>%1 (expert)</source>
        <translation>%1 (Experte)</translation>
    </message>
    <message>
        <source>When to change it</source>
        <translation>Wann ändern</translation>
    </message>
    <message>
        <source>default %1</source>
        <translation>Standard %1</translation>
    </message>
    <message>
        <source>not available: “%1”</source>
        <translation>nicht verfügbar: „%1“</translation>
    </message>
</context>
<context>
    <name>hdrf::gui::StageViews</name>
    <message>
        <source>Colour (as delivered)</source>
        <translation>Farbe (wie geliefert)</translation>
    </message>
    <message>
        <source>Depth</source>
        <translation>Tiefe</translation>
    </message>
    <message>
        <source>Radiance (tone-mapped)</source>
        <translation>Radianz (tonemapped)</translation>
    </message>
    <message>
        <source>Normalized radiance</source>
        <translation>Normalisierte Radianz</translation>
    </message>
    <message>
        <source>Confidence (PCF)</source>
        <translation>Konfidenz (PCF)</translation>
    </message>
    <message>
        <source>Model radiance (ray cast)</source>
        <translation>Modellradianz (Raycast)</translation>
    </message>
    <message>
        <source>Model normals (ray cast)</source>
        <translation>Modellnormalen (Raycast)</translation>
    </message>
    <message>
        <source>depth %L1 m</source>
        <translation>Tiefe %L1 m</translation>
    </message>
    <message>
        <source>no depth</source>
        <translation>keine Tiefe</translation>
    </message>
    <message>
        <source>std</source>
        <translation>Std.-Abw.</translation>
    </message>
    <message>
        <source>PCF</source>
        <translation>PCF</translation>
    </message>
    <message>
        <source>PCF %L1 (max channel %L2)</source>
        <translation>PCF %L1 (größter Kanal %L2)</translation>
    </message>
    <message>
        <source>normal %L1 %L2 %L3, depth %L4 m</source>
        <translation>Normale %L1 %L2 %L3, Tiefe %L4 m</translation>
    </message>
    <message>
        <source>no surface</source>
        <translation>keine Fläche</translation>
    </message>
</context>
<context>
    <name>hdrf::gui::StatusPanel</name>
    <message>
        <source>No frame yet</source>
        <translation>Noch kein Bild</translation>
    </message>
    <message>
        <source>Tracking: -</source>
        <translation>Tracking: -</translation>
    </message>
    <message>
        <source>convert</source>
        <translation>Umrechnen</translation>
    </message>
    <message>
        <source>normalize</source>
        <translation>Normalisieren</translation>
    </message>
    <message>
        <source>track</source>
        <translation>Tracken</translation>
    </message>
    <message>
        <source>compensate</source>
        <translation>Ausgleichen</translation>
    </message>
    <message>
        <source>integrate</source>
        <translation>Integrieren</translation>
    </message>
    <message>
        <source>ray cast</source>
        <translation>Raycast</translation>
    </message>
    <message>
        <source>total</source>
        <translation>gesamt</translation>
    </message>
    <message>
        <source>Frame %1%2 on the %3</source>
        <translation>Bild %1%2 auf der %3</translation>
    </message>
    <message>
        <source>%1 % of the view lies beyond %L2 m, past the model&apos;s ray cast: tracking uses nearer surfaces (volume.raycast_far_m)</source>
        <translation>%1 % der Ansicht liegen weiter als %L2 m, jenseits des Raycasts des Modells: das Tracking nutzt nähere Flächen (volume.raycast_far_m)</translation>
    </message>
    <message>
        <source>WAITING: %1</source>
        <translation>WARTET: %1</translation>
    </message>
    <message>
        <source>TRACKING LOST: %1 (frame not fused)</source>
        <translation>TRACKING VERLOREN: %1 (Bild nicht fusioniert)</translation>
    </message>
    <message>
        <source>FOUND AGAIN, CONFIRMING: %1 (frame not fused)</source>
        <translation>WIEDERGEFUNDEN, WIRD BESTÄTIGT: %1 (Bild nicht fusioniert)</translation>
    </message>
    <message>
        <source>Tracking quality %1 %: SLOW DOWN (%2 % of pixels matched)</source>
        <translation>Tracking-Qualität %1 %: LANGSAMER BEWEGEN (%2 % der Pixel zugeordnet)</translation>
    </message>
    <message>
        <source>Tracking quality %1 % (%2 % of pixels matched)</source>
        <translation>Tracking-Qualität %1 % (%2 % der Pixel zugeordnet)</translation>
    </message>
    <message>
        <source>Relocalised from an earlier view</source>
        <translation>Aus einer früheren Ansicht relokalisiert</translation>
    </message>
    <message>
        <source>The scan&apos;s view at frame %1</source>
        <translation>Die Ansicht des Scans bei Bild %1</translation>
    </message>
    <message>
        <source>Point the camera where the scan saw this (frame %1):</source>
        <translation>Richten Sie die Kamera dorthin, wo der Scan dies sah (Bild %1):</translation>
    </message>
    <message>
        <source>%L1 ms</source>
        <translation>%L1 ms</translation>
    </message>
    <message>
        <source>%L1 ms (%L2 frames/s)</source>
        <translation>%L1 ms (%L2 Bilder/s)</translation>
    </message>
    <message>
        <source>Volume: %L1 of %L2 MiB in %3 bricks</source>
        <translation>Volumen: %L1 von %L2 MiB in %3 Bricks</translation>
    </message>
    <message>
        <source>GPU: %L1 of %L2 MiB, %3 bricks; host memory: %4 bricks (%5 moved out, %6 back)</source>
        <translation>GPU: %L1 von %L2 MiB, %3 Bricks; Hauptspeicher: %4 Bricks (%5 ausgelagert, %6 zurückgeholt)</translation>
    </message>
    <message>
        <source>VOLUME FULL: %1. New surfaces are not added; the model is kept and can be saved and exported.</source>
        <translation>VOLUMEN VOLL: %1. Neue Flächen werden nicht hinzugefügt; das Modell bleibt erhalten und kann gespeichert und exportiert werden.</translation>
    </message>
    <message>
        <source>Live preview (not scanning); the model holds %1 frames</source>
        <translation>Live-Vorschau (kein Scan); das Modell enthält %1 Bilder</translation>
    </message>
    <message>
        <source>Live preview (not scanning)</source>
        <translation>Live-Vorschau (kein Scan)</translation>
    </message>
</context>
<context>
    <name>hdrf::gui::TonePanel</name>
    <message>
        <source>Operator</source>
        <translation>Operator</translation>
    </message>
    <message>
        <source>Display</source>
        <translation>Display</translation>
    </message>
    <message>
        <source>Custom</source>
        <translation>Benutzerdefiniert</translation>
    </message>
</context>
<context>
    <name>hdrf::gui::VtkView</name>
    <message>
        <source>&lt;span style=&apos;color:#6b6b75&apos;&gt;&amp;#9632;&lt;/span&gt; floor grid, %1 m squares &amp;nbsp; axes: &lt;span style=&apos;color:#ff5050&apos;&gt;x&lt;/span&gt; &lt;span style=&apos;color:#50e050&apos;&gt;y&lt;/span&gt; &lt;span style=&apos;color:#6090ff&apos;&gt;up&lt;/span&gt;, %2 m&lt;br&gt;&lt;span style=&apos;color:#ffd933&apos;&gt;&amp;#9632;&lt;/span&gt; camera path &amp;nbsp; &lt;span style=&apos;color:#ff4d40&apos;&gt;&amp;#9632;&lt;/span&gt; camera now &amp;nbsp; &lt;span style=&apos;color:#73b3ff&apos;&gt;&amp;#9632;&lt;/span&gt; region the volume holds</source>
        <translation>&lt;span style=&apos;color:#6b6b75&apos;&gt;&amp;#9632;&lt;/span&gt; Bodenraster, %1-m-Quadrate &amp;nbsp; Achsen: &lt;span style=&apos;color:#ff5050&apos;&gt;x&lt;/span&gt; &lt;span style=&apos;color:#50e050&apos;&gt;y&lt;/span&gt; &lt;span style=&apos;color:#6090ff&apos;&gt;oben&lt;/span&gt;, %2 m&lt;br&gt;&lt;span style=&apos;color:#ffd933&apos;&gt;&amp;#9632;&lt;/span&gt; Kamerapfad &amp;nbsp; &lt;span style=&apos;color:#ff4d40&apos;&gt;&amp;#9632;&lt;/span&gt; Kamera jetzt &amp;nbsp; &lt;span style=&apos;color:#73b3ff&apos;&gt;&amp;#9632;&lt;/span&gt; vom Volumen erfasster Bereich</translation>
    </message>
    <message>
        <source>The 3-D view needs OpenGL 3.2, which this display does not offer</source>
        <translation>Die 3-D-Ansicht braucht OpenGL 3.2, das diese Anzeige nicht bietet</translation>
    </message>
    <message>
        <source>The 3-D view cannot draw: no offscreen OpenGL surface on this display</source>
        <translation>Die 3-D-Ansicht kann nicht zeichnen: keine OpenGL-Fläche außerhalb des Bildschirms auf dieser Anzeige</translation>
    </message>
</context>
<context>
    <name>hdrf::help</name>
    <message>
        <source>Documentation</source>
        <translation>Dokumentation</translation>
    </message>
    <message>
        <source>Back</source>
        <translation>Zurück</translation>
    </message>
    <message>
        <source>Forward</source>
        <translation>Vor</translation>
    </message>
    <message>
        <source>Contents</source>
        <translation>Inhalt</translation>
    </message>
    <message>
        <source>The documentation was not found. Looked in:
%1</source>
        <translation>Die Dokumentation wurde nicht gefunden. Gesucht in:
%1</translation>
    </message>
    <message>
        <source>Messages and what to do</source>
        <translation>Meldungen und was zu tun ist</translation>
    </message>
    <message>
        <source>Command-line reference</source>
        <translation>Referenz der Kommandozeile</translation>
    </message>
    <message>
        <source>About %1</source>
        <translation>Über %1</translation>
    </message>
    <message>
        <source>&lt;b&gt;%1&lt;/b&gt; %2&lt;p&gt;3-D scanning with true high-dynamic-range colour for auto-exposure RGB-D cameras.&lt;/p&gt;&lt;p&gt;It implements S. Li, A. Handa, Y. Zhang, A. Calway, &lt;i&gt;HDRFusion: HDR SLAM using a low-cost auto-exposure RGB-D sensor&lt;/i&gt;, 3DV 2016.&lt;/p&gt;&lt;p&gt;MIT licence. Documentation: %3&lt;/p&gt;</source>
        <translation>&lt;b&gt;%1&lt;/b&gt; %2&lt;p&gt;3-D-Scannen mit echter Hochkontrastfarbe (HDR) für RGB-D-Kameras mit Belichtungsautomatik.&lt;/p&gt;&lt;p&gt;Es setzt S. Li, A. Handa, Y. Zhang, A. Calway, &lt;i&gt;HDRFusion: HDR SLAM using a low-cost auto-exposure RGB-D sensor&lt;/i&gt;, 3DV 2016, um.&lt;/p&gt;&lt;p&gt;MIT-Lizenz. Dokumentation: %3&lt;/p&gt;</translation>
    </message>
</context>
<context>
    <name>hdrf::wizard::CalibrationWizard</name>
    <message>
        <source>Camera calibration</source>
        <translation>Kamerakalibrierung</translation>
    </message>
    <message>
        <source>failed (no message)</source>
        <translation>fehlgeschlagen (ohne Meldung)</translation>
    </message>
    <message>
        <source>Help</source>
        <translation>Hilfe</translation>
    </message>
    <message>
        <source>Calibrating a camera</source>
        <translation>Eine Kamera kalibrieren</translation>
    </message>
</context>
<context>
    <name>hdrf::wizard::CapturePage</name>
    <message>
        <source>3. Capture</source>
        <translation>3. Aufnahme</translation>
    </message>
    <message>
        <source>Each exposure is taken several times and checked for motion and flicker; a step that fails is taken again. Frames are written as they come: a capture cancelled or cut short can be resumed.</source>
        <translation>Jede Belichtung wird mehrmals aufgenommen und auf Bewegung und Flackern geprüft; ein fehlgeschlagener Schritt wird wiederholt. Bilder werden sofort geschrieben: eine abgebrochene oder unterbrochene Aufnahme lässt sich fortsetzen.</translation>
    </message>
    <message>
        <source>Sweep folder:</source>
        <translation>Ordner der Belichtungsreihe:</translation>
    </message>
    <message>
        <source>Start capture</source>
        <translation>Aufnahme starten</translation>
    </message>
    <message>
        <source>Cancel</source>
        <translation>Abbrechen</translation>
    </message>
    <message>
        <source>Resume</source>
        <translation>Fortsetzen</translation>
    </message>
    <message>
        <source>Back to Set-up</source>
        <translation>Zurück zur Einrichtung</translation>
    </message>
    <message>
        <source>The last frame captured shows here.</source>
        <translation>Das zuletzt aufgenommene Bild erscheint hier.</translation>
    </message>
    <message>
        <source>%1 exposures from %2 to %3 ms, %4 frames each.</source>
        <translation>%1 Belichtungen von %2 bis %3 ms, je %4 Bilder.</translation>
    </message>
    <message>
        <source>Choose the sweep folder.</source>
        <translation>Wählen Sie den Ordner der Belichtungsreihe.</translation>
    </message>
    <message>
        <source>Resuming the capture in %1</source>
        <translation>Aufnahme in %1 wird fortgesetzt</translation>
    </message>
    <message>
        <source>Capturing to %1</source>
        <translation>Aufnahme nach %1</translation>
    </message>
    <message>
        <source>Step %1 of %2 at %3 ms; %4 frames written; %5 steps taken again.</source>
        <translation>Schritt %1 von %2 bei %3 ms; %4 Bilder geschrieben; %5 Schritte wiederholt.</translation>
    </message>
    <message>
        <source>Step %1: %2 ms, done</source>
        <translation>Schritt %1: %2 ms, fertig</translation>
    </message>
    <message>
        <source>Stopped: %1</source>
        <translation>Gestoppt: %1</translation>
    </message>
    <message>
        <source>Cancelled: %1 of %2 steps (%3 frames) kept in %4. Resume to complete it.</source>
        <translation>Abgebrochen: %1 von %2 Schritten (%3 Bilder) in %4 behalten. Fortsetzen, um sie zu vervollständigen.</translation>
    </message>
    <message>
        <source>Complete: %1 steps, %2 frames, %3 steps taken again.</source>
        <translation>Vollständig: %1 Schritte, %2 Bilder, %3 Schritte wiederholt.</translation>
    </message>
</context>
<context>
    <name>hdrf::wizard::FitPage</name>
    <message>
        <source>4. Fit</source>
        <translation>4. Anpassung</translation>
    </message>
    <message>
        <source>The camera response, its noise level function and the pixel confidence, fitted to the sweep.</source>
        <translation>Die Antwortkurve der Kamera, ihre Rauschfunktion und die Pixelkonfidenz, an die Belichtungsreihe angepasst.</translation>
    </message>
    <message>
        <source>Method:</source>
        <translation>Verfahren:</translation>
    </message>
    <message>
        <source>Debevec &amp; Malik (recommended)</source>
        <translation>Debevec &amp; Malik (empfohlen)</translation>
    </message>
    <message>
        <source>Robertson et al.</source>
        <translation>Robertson u. a.</translation>
    </message>
    <message>
        <source>EMoR (Grossberg &amp; Nayar)</source>
        <translation>EMoR (Grossberg &amp; Nayar)</translation>
    </message>
    <message>
        <source>invemor.txt (EMoR basis)</source>
        <translation>invemor.txt (EMoR-Basis)</translation>
    </message>
    <message>
        <source>Fit again</source>
        <translation>Erneut anpassen</translation>
    </message>
    <message>
        <source>needs its basis file invemor.txt</source>
        <translation>benötigt seine Basisdatei invemor.txt</translation>
    </message>
    <message>
        <source>Go back and capture a new sweep (or choose another folder).</source>
        <translation>Gehen Sie zurück und nehmen Sie eine neue Belichtungsreihe auf (oder wählen Sie einen anderen Ordner).</translation>
    </message>
    <message>
        <source>done</source>
        <translation>fertig</translation>
    </message>
    <message>
        <source>&lt;b&gt;%1&lt;/b&gt;: rms log residual R %L2, G %L3, B %L4.</source>
        <translation>&lt;b&gt;%1&lt;/b&gt;: RMS-Log-Residuum R %L2, G %L3, B %L4.</translation>
    </message>
    <message>
        <source> Noise: σs %L1 / %L2 / %L3, σc %L4 / %L5 / %L6.</source>
        <translation> Rauschen: σs %L1 / %L2 / %L3, σc %L4 / %L5 / %L6.</translation>
    </message>
    <message>
        <source> Noise not fitted: %1</source>
        <translation> Rauschen nicht angepasst: %1</translation>
    </message>
</context>
<context>
    <name>hdrf::wizard::PlotWidget</name>
    <message>
        <source>no data yet</source>
        <translation>noch keine Daten</translation>
    </message>
</context>
<context>
    <name>hdrf::wizard::Plots</name>
    <message>
        <source>red</source>
        <translation>rot</translation>
    </message>
    <message>
        <source>green</source>
        <translation>grün</translation>
    </message>
    <message>
        <source>blue</source>
        <translation>blau</translation>
    </message>
    <message>
        <source>Inverse response f⁻¹ (</source>
        <translation>Inverse Antwort f⁻¹ (</translation>
    </message>
    <message>
        <source>level</source>
        <translation>Stufe</translation>
    </message>
    <message>
        <source>radiance × exposure (f⁻¹(128) = 1)</source>
        <translation>Radianz × Belichtung (f⁻¹(128) = 1)</translation>
    </message>
    <message>
        <source>Response derivative f′</source>
        <translation>Ableitung der Antwort f′</translation>
    </message>
    <message>
        <source>levels per unit of radiance</source>
        <translation>Stufen je Radianzeinheit</translation>
    </message>
    <message>
        <source>radiance R</source>
        <translation>Radianz R</translation>
    </message>
    <message>
        <source>variance of R</source>
        <translation>Varianz von R</translation>
    </message>
    <message>
        <source> (fit)</source>
        <translation> (Anpassung)</translation>
    </message>
    <message>
        <source>Pixel confidence p0..p3 (green)</source>
        <translation>Pixelkonfidenz p0..p3 (grün)</translation>
    </message>
    <message>
        <source>confidence</source>
        <translation>Konfidenz</translation>
    </message>
    <message>
        <source>Residual per level (median, against the merge)</source>
        <translation>Residuum je Stufe (Median, gegen die Zusammenführung)</translation>
    </message>
    <message>
        <source>stops</source>
        <translation>Blendenstufen</translation>
    </message>
    <message>
        <source>Each exposure against the merge of all</source>
        <translation>Jede Belichtung gegen die Zusammenführung aller</translation>
    </message>
    <message>
        <source>exposure (ms)</source>
        <translation>Belichtung (ms)</translation>
    </message>
    <message>
        <source>median |deviation| (stops)</source>
        <translation>Median |Abweichung| (Blendenstufen)</translation>
    </message>
    <message>
        <source>every exposure</source>
        <translation>jede Belichtung</translation>
    </message>
    <message>
        <source>held back, predicted from the others</source>
        <translation>zurückgehalten, aus den anderen vorhergesagt</translation>
    </message>
    <message>
        <source>good</source>
        <translation>gut</translation>
    </message>
    <message>
        <source>redo</source>
        <translation>wiederholen</translation>
    </message>
    <message>
        <source>Noise level function Var R = R·σs² + σc²</source>
        <translation>Rauschfunktion Var R = R·σs² + σc²</translation>
    </message>
</context>
<context>
    <name>hdrf::wizard::SavePage</name>
    <message>
        <source>6. Save</source>
        <translation>6. Speichern</translation>
    </message>
    <message>
        <source>The profile is stored for the device&apos;s serial: the studio and the command-line tools use it whenever that camera is connected. The report keeps the plots and figures.</source>
        <translation>Das Profil wird unter der Seriennummer des Geräts abgelegt: das Studio und die Kommandozeilenwerkzeuge verwenden es, sobald diese Kamera angeschlossen ist. Der Bericht bewahrt die Diagramme und Kennzahlen.</translation>
    </message>
    <message>
        <source>Device serial:</source>
        <translation>Seriennummer des Geräts:</translation>
    </message>
    <message>
        <source>Profile file:</source>
        <translation>Profildatei:</translation>
    </message>
    <message>
        <source>Report folder:</source>
        <translation>Berichtsordner:</translation>
    </message>
    <message>
        <source>Save profile and report</source>
        <translation>Profil und Bericht speichern</translation>
    </message>
    <message>
        <source>(give the serial)</source>
        <translation>(Seriennummer angeben)</translation>
    </message>
    <message>
        <source>Give the device&apos;s serial to store the profile under.</source>
        <translation>Geben Sie die Seriennummer des Geräts an, unter der das Profil abgelegt wird.</translation>
    </message>
    <message>
        <source>Saved the profile %1 and the report %2.</source>
        <translation>Profil %1 und Bericht %2 gespeichert.</translation>
    </message>
</context>
<context>
    <name>hdrf::wizard::SetupPage</name>
    <message>
        <source>2. Set-up</source>
        <translation>2. Einrichtung</translation>
    </message>
    <message>
        <source>Lock the automatic controls, point the camera, and check that the planned sweep covers every level before capturing.</source>
        <translation>Die Automatiken sperren, die Kamera ausrichten und prüfen, dass die geplante Belichtungsreihe jede Stufe abdeckt, bevor aufgenommen wird.</translation>
    </message>
    <message>
        <source>&lt;b&gt;Before you capture&lt;/b&gt;&lt;ul&gt;&lt;li&gt;Camera on a tripod or a table: it must not move during the sweep.&lt;/li&gt;&lt;li&gt;A static scene with dark and bright parts and many shades between (not a white wall or a grey card); nobody walking through.&lt;/li&gt;&lt;li&gt;No flickering light: fluorescent tubes and dimmed LEDs change brightness with the mains; daylight or incandescent light is steady.&lt;/li&gt;&lt;/ul&gt;</source>
        <translation>&lt;b&gt;Vor der Aufnahme&lt;/b&gt;&lt;ul&gt;&lt;li&gt;Kamera auf einem Stativ oder Tisch: sie darf sich während der Belichtungsreihe nicht bewegen.&lt;/li&gt;&lt;li&gt;Eine statische Szene mit dunklen und hellen Teilen und vielen Abstufungen dazwischen (keine weiße Wand, keine Graukarte); niemand läuft hindurch.&lt;/li&gt;&lt;li&gt;Kein flackerndes Licht: Leuchtstoffröhren und gedimmte LEDs ändern ihre Helligkeit mit dem Netz; Tageslicht und Glühlampen sind gleichmäßig.&lt;/li&gt;&lt;/ul&gt;</translation>
    </message>
    <message>
        <source>Automatic controls</source>
        <translation>Automatiken</translation>
    </message>
    <message>
        <source>Lock auto exposure (off)</source>
        <translation>Belichtungsautomatik sperren (aus)</translation>
    </message>
    <message>
        <source>Lock white balance (off)</source>
        <translation>Weißabgleich sperren (aus)</translation>
    </message>
    <message>
        <source>Sweep plan</source>
        <translation>Plan der Belichtungsreihe</translation>
    </message>
    <message>
        <source> stops</source>
        <translation> Blendenstufen</translation>
    </message>
    <message>
        <source>Step between exposures:</source>
        <translation>Schritt zwischen Belichtungen:</translation>
    </message>
    <message>
        <source>Frames per exposure: 3 or more measure the noise</source>
        <translation>Bilder je Belichtung: 3 oder mehr messen das Rauschen</translation>
    </message>
    <message>
        <source>Frames per exposure:</source>
        <translation>Bilder je Belichtung:</translation>
    </message>
    <message>
        <source> ms</source>
        <translation> ms</translation>
    </message>
    <message>
        <source>metered from the scene</source>
        <translation>aus der Szene gemessen</translation>
    </message>
    <message>
        <source>Shortest exposure:</source>
        <translation>Kürzeste Belichtung:</translation>
    </message>
    <message>
        <source>Longest exposure:</source>
        <translation>Längste Belichtung:</translation>
    </message>
    <message>
        <source>Check the plan</source>
        <translation>Plan prüfen</translation>
    </message>
    <message>
        <source>Preview (red: saturated, blue: black)</source>
        <translation>Vorschau (rot: gesättigt, blau: schwarz)</translation>
    </message>
    <message>
        <source>Preview exposure:</source>
        <translation>Vorschaubelichtung:</translation>
    </message>
    <message>
        <source>As the camera reports it: auto exposure &lt;b&gt;%1&lt;/b&gt;, auto white balance &lt;b&gt;%2&lt;/b&gt;.</source>
        <translation>Wie die Kamera es meldet: Belichtungsautomatik &lt;b&gt;%1&lt;/b&gt;, automatischer Weißabgleich &lt;b&gt;%2&lt;/b&gt;.</translation>
    </message>
    <message>
        <source>on</source>
        <translation>an</translation>
    </message>
    <message>
        <source>off</source>
        <translation>aus</translation>
    </message>
    <message>
        <source>Histogram: %L1 % saturated, %L2 % black</source>
        <translation>Histogramm: %L1 % gesättigt, %L2 % schwarz</translation>
    </message>
    <message>
        <source>level</source>
        <translation>Stufe</translation>
    </message>
    <message>
        <source>pixels</source>
        <translation>Pixel</translation>
    </message>
    <message>
        <source>Metering the scene and taking a preview sweep…</source>
        <translation>Szene wird gemessen und eine Vorschau-Belichtungsreihe aufgenommen…</translation>
    </message>
    <message>
        <source>&lt;b&gt;Plan:&lt;/b&gt; %1 exposures from %2 to %3 ms, %4 frames each (%5 frames). Levels covered by the preview sweep: %6.</source>
        <translation>&lt;b&gt;Plan:&lt;/b&gt; %1 Belichtungen von %2 bis %3 ms, je %4 Bilder (%5 Bilder). Von der Vorschau-Belichtungsreihe abgedeckte Stufen: %6.</translation>
    </message>
</context>
<context>
    <name>hdrf::wizard::SourcePage</name>
    <message>
        <source>1. Source</source>
        <translation>1. Quelle</translation>
    </message>
    <message>
        <source>Where the exposure sweep comes from: a camera (captured on the next pages), a sweep recorded earlier, or the synthetic sensor (no hardware; its true response is known).</source>
        <translation>Woher die Belichtungsreihe kommt: eine Kamera (auf den nächsten Seiten aufgenommen), eine früher aufgenommene Belichtungsreihe oder der synthetische Sensor (keine Hardware; seine wahre Antwortkurve ist bekannt).</translation>
    </message>
    <message>
        <source>Live camera (OpenNI2)</source>
        <translation>Live-Kamera (OpenNI2)</translation>
    </message>
    <message>
        <source>Recorded sweep folder</source>
        <translation>Ordner einer aufgenommenen Belichtungsreihe</translation>
    </message>
    <message>
        <source>Synthetic sensor</source>
        <translation>Synthetischer Sensor</translation>
    </message>
    <message>
        <source>Refresh</source>
        <translation>Aktualisieren</translation>
    </message>
    <message>
        <source>Device:</source>
        <translation>Gerät:</translation>
    </message>
    <message>
        <source>VGA 640×480</source>
        <translation>VGA 640×480</translation>
    </message>
    <message>
        <source>QVGA 320×240</source>
        <translation>QVGA 320×240</translation>
    </message>
    <message>
        <source>Mode:</source>
        <translation>Modus:</translation>
    </message>
    <message>
        <source>from the profile (else the device&apos;s raw unit)</source>
        <translation>aus dem Profil (sonst die Roheinheit des Geräts)</translation>
    </message>
    <message>
        <source> ms</source>
        <translation> ms</translation>
    </message>
    <message>
        <source>How long one step of the device&apos;s exposure setting is. Unknown: exposures are recorded in the device&apos;s raw unit, which is assumed linear in time.</source>
        <translation>Wie lang ein Schritt der Belichtungseinstellung des Geräts ist. Unbekannt: Belichtungen werden in der Roheinheit des Geräts aufgezeichnet, die als linear in der Zeit angenommen wird.</translation>
    </message>
    <message>
        <source>Exposure step:</source>
        <translation>Belichtungsschritt:</translation>
    </message>
    <message>
        <source>folder with rgb.txt, exposure.txt and sensor.json</source>
        <translation>Ordner mit rgb.txt, exposure.txt und sensor.json</translation>
    </message>
    <message>
        <source>Browse…</source>
        <translation>Durchsuchen…</translation>
    </message>
    <message>
        <source>Sweep folder</source>
        <translation>Ordner der Belichtungsreihe</translation>
    </message>
    <message>
        <source>Asus Xtion (measured)</source>
        <translation>Asus Xtion (gemessen)</translation>
    </message>
    <message>
        <source>sRGB</source>
        <translation>sRGB</translation>
    </message>
    <message>
        <source>Gamma 2.2</source>
        <translation>Gamma 2.2</translation>
    </message>
    <message>
        <source>Gamma 1.8</source>
        <translation>Gamma 1.8</translation>
    </message>
    <message>
        <source>Linear</source>
        <translation>Linear</translation>
    </message>
    <message>
        <source>From a sensor.json…</source>
        <translation>Aus einer sensor.json…</translation>
    </message>
    <message>
        <source>True response:</source>
        <translation>Wahre Antwortkurve:</translation>
    </message>
    <message>
        <source>sensor.json whose response (and noise) the sensor takes</source>
        <translation>sensor.json, deren Antwortkurve (und Rauschen) der Sensor übernimmt</translation>
    </message>
    <message>
        <source>Response file:</source>
        <translation>Antwortdatei:</translation>
    </message>
    <message>
        <source>Room</source>
        <translation>Raum</translation>
    </message>
    <message>
        <source>Desk</source>
        <translation>Schreibtisch</translation>
    </message>
    <message>
        <source>Scene:</source>
        <translation>Szene:</translation>
    </message>
    <message>
        <source>Image size:</source>
        <translation>Bildgröße:</translation>
    </message>
    <message>
        <source>no camera connected</source>
        <translation>keine Kamera angeschlossen</translation>
    </message>
    <message>
        <source>Choose the sweep folder.</source>
        <translation>Wählen Sie den Ordner der Belichtungsreihe.</translation>
    </message>
    <message>
        <source>No camera is connected: plug one in and press Refresh, or choose the synthetic sensor.</source>
        <translation>Keine Kamera angeschlossen: schließen Sie eine an und drücken Sie Aktualisieren, oder wählen Sie den synthetischen Sensor.</translation>
    </message>
</context>
<context>
    <name>hdrf::wizard::ValidatePage</name>
    <message>
        <source>5. Validate</source>
        <translation>5. Prüfung</translation>
    </message>
    <message>
        <source>Every exposure against the merge of all, and the middle exposure held back and predicted from a fit without it.</source>
        <translation>Jede Belichtung gegen die Zusammenführung aller, und die mittlere Belichtung zurückgehalten und aus einer Anpassung ohne sie vorhergesagt.</translation>
    </message>
    <message>
        <source>Good</source>
        <translation>Gut</translation>
    </message>
    <message>
        <source>Marginal</source>
        <translation>Grenzwertig</translation>
    </message>
    <message>
        <source>Redo</source>
        <translation>Wiederholen</translation>
    </message>
    <message>
        <source>Verdict: %1</source>
        <translation>Urteil: %1</translation>
    </message>
    <message>
        <source>Held back %L1 ms: predicted from the others within %L2 stops (median). Levels covered: %3. Noise level function: %4.</source>
        <translation>Zurückgehalten %L1 ms: aus den anderen auf %L2 Blendenstufen genau vorhergesagt (Median). Abgedeckte Stufen: %3. Rauschfunktion: %4.</translation>
    </message>
    <message>
        <source>saved</source>
        <translation>gespeichert</translation>
    </message>
    <message>
        <source>not saved</source>
        <translation>nicht gespeichert</translation>
    </message>
    <message>
        <source>&lt;b&gt;This calibration cannot be saved.&lt;/b&gt; Go back to Capture and take a new sweep: static camera and scene, auto exposure off, exposures from mostly dark to mostly saturated.</source>
        <translation>&lt;b&gt;Diese Kalibrierung kann nicht gespeichert werden.&lt;/b&gt; Gehen Sie zurück zur Aufnahme und nehmen Sie eine neue Belichtungsreihe auf: Kamera und Szene unbewegt, Belichtungsautomatik aus, Belichtungen von überwiegend dunkel bis überwiegend gesättigt.</translation>
    </message>
    <message>
        <source>It can be saved; a new sweep may do better.</source>
        <translation>Sie kann gespeichert werden; eine neue Belichtungsreihe kann besser ausfallen.</translation>
    </message>
    <message>
        <source>verdict redo: %1</source>
        <translation>Urteil „wiederholen“: %1</translation>
    </message>
</context>
</TS>
