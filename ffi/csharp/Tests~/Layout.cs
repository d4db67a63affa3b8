// Prints what the C# declarations say about the C ABI, for ffi/tests/csharp.rs to compare
// with springwater.h compiled by the C compiler:
//   fn NAME RETURN PARAM...          every [DllImport] of Native (C# type names)
//   struct NAME SIZE                 every Sw* struct (Marshal.SizeOf)
//   field STRUCT.NAME OFFSET SIZE TYPE   its fields (Marshal.OffsetOf; TYPE[N] for fixed buffers)
//   const NAME VALUE                 every constant of Native
using System;
using System.Linq;
using System.Reflection;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;
using Springwater;

static class Layout
{
    static void Main()
    {
        foreach (MethodInfo m in typeof(Native).GetMethods(BindingFlags.Public | BindingFlags.Static))
        {
            var import = m.GetCustomAttributes(typeof(DllImportAttribute), false)
                .Cast<DllImportAttribute>().FirstOrDefault();
            if (import == null)
                continue;
            string entry = string.IsNullOrEmpty(import.EntryPoint) ? m.Name : import.EntryPoint;
            string convention = import.CallingConvention == CallingConvention.Cdecl ? "" : " NOT-CDECL";
            var parameters = m.GetParameters().Select(p => Name(p.ParameterType));
            Console.WriteLine("fn " + entry + " " + Name(m.ReturnType) + " " + string.Join(" ", parameters) + convention);
        }
        foreach (Type t in typeof(Native).Assembly.GetTypes()
                     .Where(t => t.IsValueType && t.Namespace == "Springwater" && t.Name.StartsWith("Sw")))
        {
            Console.WriteLine("struct " + t.Name + " " + Marshal.SizeOf(t));
            foreach (FieldInfo f in t.GetFields(BindingFlags.Public | BindingFlags.NonPublic | BindingFlags.Instance))
            {
                var fixedBuffer = f.GetCustomAttributes(typeof(FixedBufferAttribute), false)
                    .Cast<FixedBufferAttribute>().FirstOrDefault();
                string type = fixedBuffer == null
                    ? Name(f.FieldType)
                    : Name(fixedBuffer.ElementType) + "[" + fixedBuffer.Length + "]";
                Console.WriteLine("field " + t.Name + "." + f.Name + " " + Marshal.OffsetOf(t, f.Name)
                    + " " + Marshal.SizeOf(f.FieldType) + " " + type);
            }
        }
        foreach (FieldInfo f in typeof(Native).GetFields(BindingFlags.Public | BindingFlags.Static))
            if (f.IsLiteral && f.FieldType == typeof(int))
                Console.WriteLine("const " + f.Name + " " + f.GetRawConstantValue());
    }

    /// C# spelling of a type: int, uint, float*, IntPtr*, SwParams, ...
    static string Name(Type t)
    {
        if (t.IsPointer)
            return Name(t.GetElementType()) + "*";
        switch (t.FullName)
        {
            case "System.Void": return "void";
            case "System.Byte": return "byte";
            case "System.Int32": return "int";
            case "System.UInt32": return "uint";
            case "System.Int64": return "long";
            case "System.UInt64": return "ulong";
            case "System.Single": return "float";
            case "System.Double": return "double";
            default: return t.Name;
        }
    }
}
