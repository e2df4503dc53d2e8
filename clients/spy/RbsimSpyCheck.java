// rbsim-spy --check: what lcm-spy would decode, without opening a window.
//
// lcm-spy decodes a channel by looking the message's fingerprint up in its
// LCMTypeDatabase, which scans the class path for LCM types. So for every
// expected rbsim type this loads the class, reads its LCM_FINGERPRINT and
// asks a fresh LCMTypeDatabase for it, exactly as the spy does. It also loads
// the spy and the chart library its field viewer needs.
//
// usage: java -cp lcm.jar:jchart2d.jar:TYPES_JAR RbsimSpyCheck.java TYPES_JAR [TYPE...]
// TYPE: a short name (ack_t) in package rbsim; none = every rbsim class in TYPES_JAR.
// Exit status 0 when everything was found, 1 otherwise.

import java.util.ArrayList;
import java.util.Enumeration;
import java.util.List;
import java.util.jar.JarEntry;
import java.util.jar.JarFile;

public class RbsimSpyCheck {
  public static void main(String[] args) throws Exception {
    if (args.length < 1) {
      System.err.println("usage: RbsimSpyCheck TYPES_JAR [TYPE...]");
      System.exit(2);
    }
    List<String> expected = new ArrayList<>();
    for (int i = 1; i < args.length; ++i) expected.add(args[i]);
    if (expected.isEmpty()) expected = typesInJar(args[0]);
    if (expected.isEmpty()) {
      System.out.println("FAIL no rbsim types expected and none in " + args[0]);
      System.exit(1);
    }

    int failures = 0;
    failures += checkLoads("lcm.spy.Spy", "lcm-spy itself (lcm.jar)");
    failures += checkLoads("info.monitorenter.gui.chart.Chart2D", "the field viewer's charts (jchart2d.jar)");

    lcm.spy.LCMTypeDatabase database = new lcm.spy.LCMTypeDatabase();
    for (String name : expected) {
      String className = "rbsim." + name;
      Class<?> type;
      long fingerprint;
      try {
        type = Class.forName(className);
        fingerprint = type.getField("LCM_FINGERPRINT").getLong(null);
      } catch (ClassNotFoundException | NoClassDefFoundError e) {
        System.out.println("FAIL " + className + ": not on the class path");
        ++failures;
        continue;
      } catch (ReflectiveOperationException e) {
        System.out.println("FAIL " + className + ": not an LCM type (" + e + ")");
        ++failures;
        continue;
      }
      Class<?> found = database.getClassByFingerprint(fingerprint);
      if (found == null || !found.getName().equals(className)) {
        System.out.println("FAIL " + className + ": lcm-spy's type database does not find it");
        ++failures;
      } else {
        System.out.printf("ok   %s fingerprint 0x%016x%n", className, fingerprint);
      }
    }
    System.out.println(failures == 0
        ? "rbsim-spy: all " + expected.size() + " rbsim types found"
        : "rbsim-spy: " + failures + " problem(s)");
    System.exit(failures == 0 ? 0 : 1);
  }

  static int checkLoads(String className, String what) {
    try {
      Class.forName(className, false, RbsimSpyCheck.class.getClassLoader());
      System.out.println("ok   " + className + " (" + what + ")");
      return 0;
    } catch (ClassNotFoundException | NoClassDefFoundError e) {
      System.out.println("FAIL " + className + " (" + what + "): " + e);
      return 1;
    }
  }

  static List<String> typesInJar(String path) throws Exception {
    List<String> names = new ArrayList<>();
    try (JarFile jar = new JarFile(path)) {
      for (Enumeration<JarEntry> e = jar.entries(); e.hasMoreElements();) {
        String entry = e.nextElement().getName();
        if (entry.startsWith("rbsim/") && entry.endsWith(".class") && !entry.contains("$"))
          names.add(entry.substring("rbsim/".length(), entry.length() - ".class".length()));
      }
    }
    return names;
  }
}
